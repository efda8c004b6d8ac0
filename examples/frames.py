"""Reading a run's particle frames with the Python standard library only, for the examples' analysis
scripts (which must run on a machine without numpy or the pmech Python package; with them, use
pmech.Run from python/ instead).

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    from frames import frames, last_frame, read_vtu
"""
import os
import re
import struct

# VTK data types of the arrays pmech writes, as struct codes
TYPES = {"Float64": "d", "Int32": "i", "Int64": "q", "UInt8": "B"}


def read_vtu(path):
    """The particles of one frame (pmech's raw appended VTU): {"n": count, name: flat tuple, ...}."""
    raw = open(path, "rb").read()
    head_end = raw.index(b'<AppendedData encoding="raw">')
    head = raw[:head_end].decode()
    base = raw.index(b"_", head_end) + 1
    out = {"n": int(re.search(r'NumberOfPoints="(\d+)"', head).group(1))}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)"([^>]*)format="appended" offset="(\d+)"', head):
        code = TYPES.get(m.group(1))
        if code is None:
            continue
        off = int(m.group(4))
        nb = struct.unpack_from("<Q", raw, base + off)[0]
        out[m.group(2)] = struct.unpack_from("<%d%s" % (nb // struct.calcsize(code), code), raw, base + off + 8)
    return out


def frames(d):
    """The frames of run directory d, from its particles.pvd: [(time, path), ...] in time order."""
    pvd = open(os.path.join(d, "particles.pvd")).read()
    return [(float(t), os.path.join(d, f)) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd)]


def last_frame(d):
    """The last frame of run directory d: (time, path)."""
    return frames(d)[-1]
