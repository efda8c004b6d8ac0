"""pmech from Python: load a case, change it key by key, run it, read what it wrote as numpy arrays.

    import pmech
    case = pmech.Case("examples/slope_fos/case.json")
    case["materials[0].friction_angle"] = 30      # the same checks as the case file
    run = case.run("slope.out", threads=1)
    energy = run.energy                           # numpy structured array: time, kinetic, ...
    last = run.frame(-1)                          # particles: positions, every field of the frame
    fos = case.factor_of_safety()                 # strength reduction

The package calls libpmech.so through ctypes (see pmech._lib for where it looks); plotting helpers are
in pmech.plot (matplotlib).
"""
import ctypes
import json
import os

import numpy as np

from . import _lib

__all__ = ["Case", "Run", "Frame", "InputError", "SimulationError", "PmechError", "frames", "version"]
__version__ = "0.1.0"


class PmechError(RuntimeError):
    """A failure reported by the library, with its message (which names the file, key path or step)."""


class InputError(PmechError, ValueError):
    """Invalid input: a case file, a key path or a value the case refuses."""


class SimulationError(PmechError):
    """The simulation failed (diverged); the outputs written so far stay valid."""


def _raise(rc):
    msg = _lib.message()
    if rc == _lib.PM_EINPUT:
        raise InputError(msg)
    if rc == -2:
        raise SimulationError(msg)
    raise PmechError(msg)


def _b(s):
    return None if s is None else os.fsencode(s) if not isinstance(s, bytes) else s


def version():
    """The version of the Python package (the library's is in every run.json)."""
    return __version__


class Case:
    """A loaded case. Keys are read and set by key path, as docs/input.md names them:
    ``case["materials[0].friction_angle"] = 30``; a refused value raises InputError and leaves the case
    as it was."""

    def __init__(self, path=None, *, text=None, name=None):
        if (path is None) == (text is None):
            raise TypeError("Case(path) or Case(text=..., name=...)")
        ptr = ctypes.c_void_p()
        rc = _lib.pm_case_new(_b(path), None if text is None else text.encode(), _b(name), ctypes.byref(ptr))
        if rc:
            _raise(rc)
        self._c = ptr

    @classmethod
    def from_dict(cls, d, name="case.json"):
        """A case from a dict shaped like a case file; ``name`` places it for relative paths."""
        return cls(text=json.dumps(d), name=name)

    def __del__(self):
        c = getattr(self, "_c", None)
        if c:
            _lib.pm_case_destroy(c)
            self._c = None

    def __setitem__(self, path, value):
        rc = _lib.pm_case_set_json(self._c, path.encode(), json.dumps(value).encode())
        if rc:
            _raise(rc)

    def __getitem__(self, path):
        p = _lib.pm_case_get_json(self._c, path.encode())
        if not p:
            raise KeyError(_lib.message())
        try:
            return json.loads(ctypes.string_at(p).decode())
        finally:
            _lib.libc_free(p)

    def __delitem__(self, path):
        rc = _lib.pm_case_remove(self._c, path.encode())
        if rc:
            _raise(rc)

    def __contains__(self, path):
        try:
            self[path]
            return True
        except KeyError:
            return False

    def to_dict(self):
        """The case as a dict (with every change made)."""
        return self[""]

    def save(self, path):
        """Write the case, with its changes, as a case file."""
        with open(path, "w") as f:
            json.dump(self.to_dict(), f, indent=2)
            f.write("\n")

    @property
    def warnings(self):
        """Values that are valid but almost surely mistakes (a modulus below 1 kPa, ...)."""
        n = _lib.pm_case_warnings(self._c, None, 0)
        buf = ctypes.create_string_buffer(_lib.WARNING_LEN * max(n, 1))
        _lib.pm_case_warnings(self._c, buf, n)
        return [buf.raw[k * _lib.WARNING_LEN:(k + 1) * _lib.WARNING_LEN].split(b"\0", 1)[0].decode()
                for k in range(n)]

    def run(self, out_dir=None, threads=1, quiet=True):
        """Run the case to its end time, writing every output into ``out_dir`` (default: the case's
        output.directory); returns a Run. A diverging run raises SimulationError (its outputs so far
        remain in the directory)."""
        stats = _lib.RunStats()
        rc = _lib.pm_run_to(self._c, _b(out_dir), int(threads), int(bool(quiet)), ctypes.byref(stats))
        if rc:
            _raise(rc)
        return Run(out_dir if out_dir is not None else self.output_dir)

    @property
    def output_dir(self):
        """Where run() writes without an out_dir: output.directory, or <case file stem>.out."""
        return os.fsdecode(_lib.pm_case_output_dir(self._c))

    def factor_of_safety(self, out_dir="", threads=1, quiet=True):
        """Strength reduction (the case's analysis.strength_reduction, which must be set): returns
        (factor, largest factor that held, smallest that failed). ``out_dir`` "" writes no files."""
        fos, lo, hi = ctypes.c_double(), ctypes.c_double(), ctypes.c_double()
        rc = _lib.pm_strength_reduction_to(self._c, _b(out_dir), int(threads), int(bool(quiet)), ctypes.byref(fos),
                                           ctypes.byref(lo), ctypes.byref(hi))
        if rc:
            _raise(rc)
        return fos.value, lo.value, hi.value


class Frame:
    """One frame read back: ``time``, ``points`` (n x 3), and its arrays by name (``frame["pressure"]``,
    ``frame["stress"]`` is n x 4). ``frame.field("speed")`` gives the derived fields pictures use
    (speed, sxx..sxy, velocity.y, ...)."""

    def __init__(self, path):
        ptr = ctypes.c_void_p()
        rc = _lib.pm_frame_read(_b(path), ctypes.byref(ptr))
        if rc:
            _raise(rc)
        self._f = ptr
        self.path = path
        self.n = _lib.pm_frame_n_points(ptr)
        self.time = _lib.pm_frame_time(ptr)
        self.points = self._copy(_lib.pm_frame_points(ptr), 3)
        self.arrays = {}
        nc = ctypes.c_int()
        for k in range(_lib.pm_frame_n_arrays(ptr)):
            name = _lib.pm_frame_array_name(ptr, k, ctypes.byref(nc)).decode()
            self.arrays[name] = self._copy(_lib.pm_frame_array(ptr, name.encode(), None), nc.value)

    def _copy(self, p, ncomp):
        if self.n == 0:
            return np.zeros((0, ncomp)) if ncomp > 1 else np.zeros(0)
        a = np.ctypeslib.as_array(p, shape=(self.n * ncomp,)).copy()
        return a.reshape(self.n, ncomp) if ncomp > 1 else a

    def __getitem__(self, name):
        return self.arrays[name]

    def keys(self):
        return self.arrays.keys()

    def field(self, name):
        """Values of a picture field (pmech render --help lists them); returns (values, unit)."""
        out = np.zeros(max(self.n, 1))
        unit = ctypes.c_char_p()
        rc = _lib.pm_frame_field(self._f, name.encode(), out.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
                                 ctypes.byref(unit), None)
        if rc:
            _raise(rc)
        return out[:self.n], unit.value.decode()

    def __del__(self):
        f = getattr(self, "_f", None)
        if f:
            _lib.pm_frame_free(f)
            self._f = None


def frames(path):
    """The frames a .pvd (or a run directory's particles.pvd) lists: [(time, file), ...]."""
    s = _lib.Series()
    rc = _lib.pm_series_read(_b(path), ctypes.byref(s))
    try:
        if rc:
            _raise(rc)
        return [(s.time[k], s.file[k].decode()) for k in range(s.n)]
    finally:
        _lib.pm_series_free(ctypes.byref(s))


class Run:
    """The output directory of a run: run.json as ``info``, energy.csv and probes.csv as numpy structured
    arrays, the frames (particles and grid) read on demand."""

    def __init__(self, directory):
        self.dir = directory

    def _path(self, name):
        return os.path.join(self.dir, name)

    @property
    def info(self):
        with open(self._path("run.json")) as f:
            return json.load(f)

    def _csv(self, name):
        a = np.genfromtxt(self._path(name), delimiter=",", names=True, deletechars="")
        return np.atleast_1d(a)

    @property
    def energy(self):
        """time, kinetic, strain, gravity, total (J per unit thickness, or per radian)."""
        return self._csv("energy.csv")

    @property
    def probes(self):
        """time and one column per probe component (names as in probes.csv, e.g. 'A.vx')."""
        return self._csv("probes.csv")

    @property
    def frames(self):
        return frames(self.dir)

    @property
    def grid_frames(self):
        return frames(self._path("grid.pvd"))

    def frame(self, k):
        """Particle frame k (negative counts from the end)."""
        return Frame(self.frames[k][1])

    def grid_frame(self, k):
        """Grid frame k: nodal mass, velocity, boundary and contact flags."""
        return Frame(self.grid_frames[k][1])

    def render(self, field, out_dir=None, width=0, range=None, animation=None, fps=0):
        """Redraw every frame coloured by ``field`` with one colour range (like pmech render); returns
        the number of pictures. ``animation`` names a .gif or .mp4 to make of them (ffmpeg)."""
        rng = (ctypes.c_double * 2)(*range) if range is not None else None
        o = _lib.RenderDirOpts(field.encode(), int(width), ctypes.cast(rng, ctypes.POINTER(ctypes.c_double))
                               if rng is not None else None, _b(out_dir), _b(animation), float(fps), 1)
        n = ctypes.c_size_t()
        rc = _lib.pm_render_dir(_b(self.dir), ctypes.byref(o), ctypes.byref(n))
        if rc:
            _raise(rc)
        return n.value
