"""Writes the inputs of tests/cli/parts_cli_test.cpp (run here with python3):
two_parts.3mf, a 3MF with two named objects as two build items: "block", the
box [0, 2] x [0, 3] x [0, 4] (volume 24, area 52, centroid (1, 1.5, 2)), and
"pin", the unit corner tetrahedron placed at (10, 0, 0) by its item's
transform (volume 1/6, centroid (10.25, 0.25, 0.25))."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from package_3mf import write_3mf  # noqa: E402

BOX = [(x, y, z) for z in (0, 4) for y in (0, 3) for x in (0, 2)]
QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
BOX_T = [t for a, b, c, d in QUADS for t in ((a, b, c), (a, c, d))]
TET = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_T = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def obj(oid, name, v, t):
    return (f'<object id="{oid}" name="{name}" type="model"><mesh><vertices>'
            + "".join(f'<vertex x="{x}" y="{y}" z="{z}"/>' for x, y, z in v) + '</vertices><triangles>'
            + "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in t) + '</triangles></mesh></object>\n')


model = ('<?xml version="1.0" encoding="UTF-8"?>\n'
         '<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n<resources>\n'
         + obj(1, "block", BOX, BOX_T) + obj(2, "pin", TET, TET_T)
         + '</resources>\n<build><item objectid="1"/><item objectid="2" transform="1 0 0 0 1 0 0 0 1 10 0 0"/></build>\n'
         '</model>\n')
write_3mf("two_parts.3mf", model)
