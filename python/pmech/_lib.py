"""The C library behind the package: finding libpmech.so and declaring the functions used.

The library is looked for, in order, at $PMECH_LIBRARY, beside this file (a copy made when the package
was installed from a checkout whose build/ held it), in the build/ directory of the checkout this file
sits in, in the libdir pkg-config reports for pmech, and where the dynamic linker looks.
"""
import ctypes
import ctypes.util
import os
import subprocess

# Threads that wait for work sleep instead of spinning, so that a run does not fight other programs for
# the cores (docs/performance.md). OpenMP reads this once, when the library is loaded, so it is set here
# first; a value the user set is kept.
os.environ.setdefault("OMP_WAIT_POLICY", "passive")

_HERE = os.path.dirname(os.path.abspath(__file__))


def _candidates():
    env = os.environ.get("PMECH_LIBRARY")
    if env:
        yield env
    for name in sorted(os.listdir(_HERE)):
        if name.startswith("libpmech.so"):
            yield os.path.join(_HERE, name)
    yield os.path.join(_HERE, os.pardir, os.pardir, "build", "libpmech.so")
    try:
        libdir = subprocess.run(["pkg-config", "--variable=libdir", "pmech"], capture_output=True, text=True,
                                check=False).stdout.strip()
        if libdir:
            yield os.path.join(libdir, "libpmech.so")
    except OSError:
        pass
    found = ctypes.util.find_library("pmech")
    if found:
        yield found


def _load():
    tried = []
    for path in _candidates():
        if os.path.sep in path and not os.path.exists(path):
            tried.append(path)
            continue
        try:
            return ctypes.CDLL(path)
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
    raise ImportError("pmech: cannot find libpmech.so; build it (make build), install it (make install), or "
                      "set PMECH_LIBRARY to its path. Tried: " + "; ".join(tried))


lib = _load()

c_int, c_long, c_double, c_char_p, c_void_p, c_size_t = (ctypes.c_int, ctypes.c_long, ctypes.c_double,
                                                         ctypes.c_char_p, ctypes.c_void_p, ctypes.c_size_t)
P = ctypes.POINTER

WARNING_LEN = 320  # PM_WARNING_LEN


class RunStats(ctypes.Structure):
    """pm_run_stats"""
    _fields_ = [("t", c_double), ("steps", c_long), ("newton_iterations", c_long), ("step_cuts", c_long),
                ("max_displacement", c_double), ("wall_seconds", c_double)]


class Series(ctypes.Structure):
    """pm_series"""
    _fields_ = [("n", c_size_t), ("time", P(c_double)), ("file", P(c_char_p))]


class RenderDirOpts(ctypes.Structure):
    """pm_render_dir_opts"""
    _fields_ = [("field", c_char_p), ("width", c_int), ("range", P(c_double)), ("out_dir", c_char_p),
                ("animation", c_char_p), ("fps", c_double), ("quiet", c_int)]


def _fn(name, restype, *argtypes):
    f = getattr(lib, name)
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


pm_error_message = _fn("pm_error_message", c_char_p)
pm_case_new = _fn("pm_case_new", c_int, c_char_p, c_char_p, c_char_p, P(c_void_p))
pm_case_destroy = _fn("pm_case_destroy", None, c_void_p)
pm_case_set_json = _fn("pm_case_set_json", c_int, c_void_p, c_char_p, c_char_p)
pm_case_remove = _fn("pm_case_remove", c_int, c_void_p, c_char_p)
pm_case_get_json = _fn("pm_case_get_json", c_void_p, c_void_p, c_char_p)
pm_case_output_dir = _fn("pm_case_output_dir", c_char_p, c_void_p)
pm_case_warnings = _fn("pm_case_warnings", c_size_t, c_void_p, c_void_p, c_size_t)
pm_run_to = _fn("pm_run_to", c_int, c_void_p, c_char_p, c_int, c_int, P(RunStats))
pm_strength_reduction_to = _fn("pm_strength_reduction_to", c_int, c_void_p, c_char_p, c_int, c_int, P(c_double),
                               P(c_double), P(c_double))
pm_frame_read = _fn("pm_frame_read", c_int, c_char_p, P(c_void_p))
pm_frame_free = _fn("pm_frame_free", None, c_void_p)
pm_frame_n_points = _fn("pm_frame_n_points", c_size_t, c_void_p)
pm_frame_time = _fn("pm_frame_time", c_double, c_void_p)
pm_frame_points = _fn("pm_frame_points", P(c_double), c_void_p)
pm_frame_n_arrays = _fn("pm_frame_n_arrays", c_size_t, c_void_p)
pm_frame_array_name = _fn("pm_frame_array_name", c_char_p, c_void_p, c_size_t, P(c_int))
pm_frame_array = _fn("pm_frame_array", P(c_double), c_void_p, c_char_p, P(c_int))
pm_frame_field = _fn("pm_frame_field", c_int, c_void_p, c_char_p, P(c_double), P(c_char_p), P(c_int))
pm_series_read = _fn("pm_series_read", c_int, c_char_p, P(Series))
pm_series_free = _fn("pm_series_free", None, P(Series))
pm_render_dir = _fn("pm_render_dir", c_int, c_char_p, P(RenderDirOpts), P(c_size_t))
libc_free = ctypes.CDLL(None).free
libc_free.argtypes = [c_void_p]
libc_free.restype = None

PM_EINPUT = -1


def message():
    m = pm_error_message()
    return m.decode("utf-8", "replace") if m else ""
