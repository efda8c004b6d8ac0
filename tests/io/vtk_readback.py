#!/usr/bin/env python3
"""Read a pmech output directory back with VTK's own XML reader.

usage: vtk_readback.py DIR N_PARTICLES

Checks that particles.pvd is a valid Collection whose every listed frame exists, and that VTK's
vtkXMLUnstructuredGridReader reads each frame with N_PARTICLES points and N_PARTICLES vertex cells
and the point arrays displacement (3), velocity (3), grid_velocity (3), stress (4: xx, yy, zz, xy), plastic_strain,
material (Int32), body (Int32), mass, volume and id (Int32, no two particles of a frame alike) and the
derived fields, each with one finite tuple per particle. N_PARTICLES is one count for every frame, or a
comma-separated list of one count per frame in the order particles.pvd lists them (runs whose sources
and sinks change the count; a frame may hold no particle). grid.vtu, when present, must read with at
least one point and one cell; grid.pvd, when present, must list one grid frame per particle frame with
the same times, each with the flags boundary (UInt8) and contact (Int32) and, after the first, a nodal
mass whose sum is the particles' (the shape functions are a partition of unity: equal to 1e-9
relative, summation rounding). No temporary file may be left.
Exit status: 0 all good, 1 a check failed, 2 bad usage.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
except ImportError:
    # the interpreter first on PATH may lack VTK's bindings; the distribution's usually has them
    for cand in ("/usr/bin/python3",):
        if (os.path.exists(cand) and os.path.realpath(cand) != os.path.realpath(sys.executable)
                and not os.environ.get("PMECH_READBACK_REEXEC")):
            os.environ["PMECH_READBACK_REEXEC"] = "1"
            os.execv(cand, [cand] + sys.argv)
    sys.stderr.write("vtk_readback: cannot import vtk (install python3-vtk9)\n")
    sys.exit(1)

try:
    import numpy
except ImportError:
    numpy = None

EXPECTED = {  # name: (components, VTK data type or None for any floating type)
    "displacement": (3, None),
    "velocity": (3, None),
    "grid_velocity": (3, None),
    "stress": (4, None),
    "plastic_strain": (1, None),
    "material": (1, vtk.VTK_INT),
    "body": (1, vtk.VTK_INT),
    "mass": (1, None),
    "volume": (1, None),
    "pressure": (1, None),
    "q": (1, None),
    "volumetric_strain": (1, None),
    "deviatoric_strain": (1, None),
    "deformation_gradient": (5, None),
    "half_size": (2, None),
    "id": (1, vtk.VTK_INT),
}
STRESS_COMPONENTS = ["xx", "yy", "zz", "xy"]

errors = []


def fail(msg):
    errors.append(msg)
    sys.stderr.write("FAIL " + msg + "\n")


def all_finite(arr):
    """True if every value of a vtkDataArray is finite (numpy when available, else a C-level map)."""
    if arr.GetNumberOfTuples() == 0:
        return True
    mv = memoryview(arr)
    flat = mv.cast("B").cast(mv.format)
    if numpy is not None:
        return bool(numpy.isfinite(numpy.frombuffer(flat, dtype=mv.format)).all())
    if mv.format not in ("d", "f"):
        return True  # integers are always finite
    return all(map(math.isfinite, flat))


class ErrorCatcher:
    """Collects the ErrorEvent/WarningEvent messages VTK raises while reading."""

    def __init__(self):
        self.messages = []

    def __call__(self, obj, event, *args):
        self.messages.append("%s from %s" % (event, obj.GetClassName()))


def read_vtu(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    catcher = ErrorCatcher()
    reader.AddObserver("ErrorEvent", catcher)
    reader.AddObserver("WarningEvent", catcher)
    reader.SetFileName(path)
    reader.Update()
    for m in catcher.messages:
        fail("%s: VTK reported %s" % (path, m))
    if catcher.messages:
        return None
    return reader.GetOutput()


def array_sum(arr):
    return sum(arr.GetValue(i) for i in range(arr.GetNumberOfTuples() * arr.GetNumberOfComponents()))


def check_frame(path, n, t=None):
    """Checks one particle frame; returns the sum of its particle masses (None when unreadable)."""
    ug = read_vtu(path)
    if ug is None:
        return None
    tv = ug.GetFieldData().GetArray("TimeValue")
    if tv is None or tv.GetNumberOfTuples() != 1:
        fail("%s: no TimeValue field" % path)
    elif t is not None and tv.GetValue(0) != t:
        fail("%s: TimeValue %r, the collection says %r" % (path, tv.GetValue(0), t))
    if ug.GetNumberOfPoints() != n:
        fail("%s: %d points, expected %d" % (path, ug.GetNumberOfPoints(), n))
    if ug.GetNumberOfCells() != n:
        fail("%s: %d cells, expected %d" % (path, ug.GetNumberOfCells(), n))
    types = ug.GetCellTypesArray()
    if types is not None and types.GetNumberOfTuples() > 0:
        lo, hi = types.GetRange(0)
        if lo != vtk.VTK_VERTEX or hi != vtk.VTK_VERTEX:
            fail("%s: particle cells are not all VTK_VERTEX" % path)
    pts = ug.GetPoints()
    if n > 0 and (pts is None or not all_finite(pts.GetData())):
        fail("%s: point coordinates missing or not finite" % path)
    pd = ug.GetPointData()
    for name, (ncomp, vtype) in EXPECTED.items():
        arr = pd.GetArray(name)
        if arr is None:
            fail("%s: no point array '%s'" % (path, name))
            continue
        if arr.GetNumberOfComponents() != ncomp:
            fail("%s: '%s' has %d components, expected %d" % (path, name, arr.GetNumberOfComponents(), ncomp))
        if arr.GetNumberOfTuples() != n:
            fail("%s: '%s' has %d tuples, expected %d" % (path, name, arr.GetNumberOfTuples(), n))
        if vtype is not None and arr.GetDataType() != vtype:
            fail("%s: '%s' is %s, expected Int32" % (path, name, arr.GetDataTypeAsString()))
        if vtype is None and arr.GetDataType() not in (vtk.VTK_DOUBLE, vtk.VTK_FLOAT):
            fail("%s: '%s' is %s, expected a floating type" % (path, name, arr.GetDataTypeAsString()))
        if not all_finite(arr):
            fail("%s: '%s' holds values that are not finite" % (path, name))
        if name == "stress" and ncomp == arr.GetNumberOfComponents():
            got = [arr.GetComponentName(k) for k in range(ncomp)]
            if got != STRESS_COMPONENTS:
                fail("%s: stress component names %s, expected %s" % (path, got, STRESS_COMPONENTS))
        if name == "id" and arr.GetNumberOfTuples() == n:
            ids = [int(arr.GetValue(k)) for k in range(n)]
            if len(set(ids)) != n:
                fail("%s: %d particles share an id with another" % (path, n - len(set(ids))))
    mass = pd.GetArray("mass")
    return array_sum(mass) if mass is not None else None


def check_grid_frames(d, frames):
    """grid.pvd: one grid frame per particle frame (time, particle mass sum), nodal mass conserved."""
    pvd = os.path.join(d, "grid.pvd")
    try:
        sets = ET.parse(pvd).getroot().findall("./Collection/DataSet")
    except (OSError, ET.ParseError) as e:
        fail("%s: %s" % (pvd, e))
        return
    if len(sets) != len(frames):
        fail("%s lists %d frames, particles.pvd %d" % (pvd, len(sets), len(frames)))
        return
    for k, (ds, (t, pmass)) in enumerate(zip(sets, frames)):
        path = os.path.join(d, ds.get("file"))
        if float(ds.get("timestep")) != t:
            fail("%s: time %s, the particle frame's %r" % (path, ds.get("timestep"), t))
        check_grid(path)
        ug = read_vtu(path)
        if ug is None:
            continue
        pd = ug.GetPointData()
        for name, vtype in (("boundary", vtk.VTK_UNSIGNED_CHAR), ("contact", vtk.VTK_INT)):
            arr = pd.GetArray(name)
            if arr is None or arr.GetDataType() != vtype:
                fail("%s: no %s array of the right type" % (path, name))
        mass = pd.GetArray("mass")
        if k == 0:
            continue
        if mass is None:
            fail("%s: no nodal mass" % path)
        elif pmass is not None and abs(array_sum(mass) - pmass) > 1e-9 * abs(pmass):
            fail("%s: nodal mass %.17g, particle mass %.17g" % (path, array_sum(mass), pmass))


def check_grid(path):
    ug = read_vtu(path)
    if ug is None:
        return
    if ug.GetNumberOfPoints() < 1 or ug.GetNumberOfCells() < 1:
        fail("%s: %d points and %d cells" % (path, ug.GetNumberOfPoints(), ug.GetNumberOfCells()))
        return
    lo, hi = ug.GetCellTypesArray().GetRange(0)
    allowed = (vtk.VTK_VERTEX, vtk.VTK_TRIANGLE, vtk.VTK_QUAD)
    if lo not in allowed or hi not in allowed:
        fail("%s: unexpected cell types in [%d, %d]" % (path, lo, hi))
    if not all_finite(ug.GetPoints().GetData()):
        fail("%s: node coordinates are not finite" % path)


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: vtk_readback.py DIR N_PARTICLES\n")
        return 2
    d = argv[1]
    try:
        counts = [int(v) for v in argv[2].split(",")]
    except ValueError:
        sys.stderr.write("vtk_readback: N_PARTICLES must be an integer or a comma-separated list of them, got "
                         "'%s'\n" % argv[2])
        return 2
    pvd = os.path.join(d, "particles.pvd")
    try:
        root = ET.parse(pvd).getroot()
    except (OSError, ET.ParseError) as e:
        fail("%s: %s" % (pvd, e))
        return 1
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        fail("%s: not a VTKFile of type Collection" % pvd)
        return 1
    sets = root.findall("./Collection/DataSet")
    if not sets:
        fail("%s: lists no frame" % pvd)
    if len(counts) > 1 and len(counts) != len(sets):
        fail("%s: lists %d frames, %d counts were given" % (pvd, len(sets), len(counts)))
        return 1
    last = -math.inf
    frames = []
    for k, ds in enumerate(sets):
        n = counts[k] if len(counts) > 1 else counts[0]
        f = ds.get("file")
        try:
            t = float(ds.get("timestep"))
        except (TypeError, ValueError):
            fail("%s: DataSet %s has no numeric timestep" % (pvd, f))
            t = last
        if not math.isfinite(t) or t < last:
            fail("%s: timestep %r of %s is not finite or goes back in time" % (pvd, t, f))
        last = t
        if not f:
            fail("%s: DataSet without a file attribute" % pvd)
            continue
        path = os.path.join(d, f)
        if not os.path.isfile(path):
            fail("%s lists %s, which does not exist" % (pvd, f))
            continue
        frames.append((t, check_frame(path, n, t)))
    grid = os.path.join(d, "grid.vtu")
    if os.path.exists(grid):
        check_grid(grid)
    if os.path.exists(os.path.join(d, "grid.pvd")):
        check_grid_frames(d, frames)
    tmp = [f for f in os.listdir(d) if f.endswith(".tmp")]
    if tmp:
        fail("%s: temporary files left: %s" % (d, ", ".join(sorted(tmp))))
    if errors:
        return 1
    print("ok: %d frames of %s particles in %s read by VTK %s" % (len(sets), argv[2], d, vtk.vtkVersion.GetVTKVersion()))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
