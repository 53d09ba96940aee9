"""Reads a DXF as CAD would, with ezdxf (Debian's python3-ezdxf), and prints what it holds: one line
per polyline vertex (LAYER x y), per circle (CIRCLE LAYER r) and per line (LINE LAYER x1 y1 x2 y2),
numbers in full precision, then the auditor's error count. Exit 77 when ezdxf is not installed."""
import sys

try:
    import ezdxf
except ImportError:
    print("python3-ezdxf is not installed: the DXF was not read back", file=sys.stderr)
    sys.exit(77)

doc = ezdxf.readfile(sys.argv[1])
for e in doc.modelspace():
    t = e.dxftype()
    if t == "POLYLINE":
        for v in e.vertices:
            print(e.dxf.layer, repr(v.dxf.location.x), repr(v.dxf.location.y))
    elif t == "CIRCLE":
        print("CIRCLE", e.dxf.layer, repr(e.dxf.radius))
    elif t == "LINE":
        print("LINE", e.dxf.layer, repr(e.dxf.start.x), repr(e.dxf.start.y), repr(e.dxf.end.x), repr(e.dxf.end.y))
auditor = doc.audit()
print("AUDIT_ERRORS", len(auditor.errors))
print("DXFVERSION", doc.dxfversion)
