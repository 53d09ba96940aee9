"""Reads a particle series as ParaView would: the .pvd collection's data sets, each .vtp through VTK's
own XML PolyData reader. Prints one line per frame: time, points, vertices, and the ranges of the
arrays the series promises. Exit 77 when Debian's python3-vtk9 is not installed (the test skips)."""
import os
import sys
import xml.etree.ElementTree as ET

try:
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
except ImportError:
    print("python3-vtk9 is not installed: the series was not read back", file=sys.stderr)
    sys.exit(77)

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
    for name, comps in (("velocity_mps", 3), ("radius_m", 1), ("contact_force_N", 1), ("speed_mps", 1), ("id", 1)):
        a = pd.GetArray(name)
        if a is None or a.GetNumberOfComponents() != comps or a.GetNumberOfTuples() != out.GetNumberOfPoints():
            sys.exit(f"{path}: array {name} missing or of the wrong shape")
        lo, hi = a.GetRange(-1 if comps > 1 else 0)
        fields.append(f"{name}={lo:.9g}:{hi:.9g}")
    print(ds.get("timestep"), out.GetNumberOfPoints(), out.GetNumberOfVerts(), " ".join(fields))
