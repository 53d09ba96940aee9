"""Reads a particle series as ParaView would: the .pvd collection's data sets, each .vtp through VTK's
own XML PolyData reader. Prints one line per frame: time, points, vertices, the points' bounds and the
ranges of the arrays the series promises. Further arguments are legacy .vtk files (the side view, the
plate map, the walls), read through VTK's legacy reader: one line each with "legacy", the file's name,
its points and their bounds. Exit 77 when Debian's python3-vtk9 is not installed (the test skips)."""
import os
import sys
import xml.etree.ElementTree as ET

try:
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    from vtkmodules.vtkIOLegacy import vtkPolyDataReader
except ImportError:
    print("python3-vtk9 is not installed: the series was not read back", file=sys.stderr)
    sys.exit(77)


def bounds(out):
    b = out.GetBounds()
    return f"x={b[0]:.9g}:{b[1]:.9g} y={b[2]:.9g}:{b[3]:.9g} z={b[4]:.9g}:{b[5]:.9g}"


pvd = sys.argv[1]
root = ET.parse(pvd).getroot()
assert root.get("type") == "Collection", root.get("type")
for ds in root.iter("DataSet"):
    path = os.path.join(os.path.dirname(pvd), ds.get("file"))
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode():
        sys.exit("VTK could not read " + path)
    out = r.GetOutput()
    pd = out.GetPointData()
    fields = []
    for name, comps in (("velocity_mps", 3), ("radius_mm", 1), ("contact_force_N", 1), ("speed_mps", 1), ("id", 1)):
        a = pd.GetArray(name)
        if a is None or a.GetNumberOfComponents() != comps or a.GetNumberOfTuples() != out.GetNumberOfPoints():
            sys.exit(f"{path}: array {name} missing or of the wrong shape")
        lo, hi = a.GetRange(-1 if comps > 1 else 0)
        fields.append(f"{name}={lo:.9g}:{hi:.9g}")
    print(ds.get("timestep"), out.GetNumberOfPoints(), out.GetNumberOfVerts(), bounds(out), " ".join(fields))

for path in sys.argv[2:]:
    r = vtkPolyDataReader()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    if out is None or out.GetNumberOfPoints() == 0:
        sys.exit("VTK could not read " + path)
    print("legacy", os.path.basename(path), out.GetNumberOfPoints(), bounds(out), "title=" + r.GetHeader())
