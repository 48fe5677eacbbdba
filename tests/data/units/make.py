"""Writes the unit test files of tests/cli/units_cli_test.cpp (run from this
directory with python3): the unit corner tetrahedron scaled by 2 (volume 4/3
in the file's unit) as a 3MF whose model says unit="inch", and as an AMF
whose root says unit="meter"."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from package_3mf import write_3mf  # noqa: E402

V = [(0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2)]
T = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]

model = ('<?xml version="1.0" encoding="UTF-8"?>\n'
         '<model unit="inch" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n'
         '<resources><object id="1" type="model"><mesh><vertices>\n'
         + "".join(f'<vertex x="{x}" y="{y}" z="{z}"/>\n' for x, y, z in V)
         + '</vertices><triangles>\n'
         + "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>\n' for a, b, c in T)
         + '</triangles></mesh></object></resources>\n<build><item objectid="1"/></build>\n</model>\n')
write_3mf("tetra_inch.3mf", model)

amf = ('<?xml version="1.0" encoding="UTF-8"?>\n<amf unit="meter">\n<object id="0"><mesh><vertices>\n'
       + "".join(f'<vertex><coordinates><x>{x}</x><y>{y}</y><z>{z}</z></coordinates></vertex>\n' for x, y, z in V)
       + '</vertices><volume>\n'
       + "".join(f'<triangle><v1>{a}</v1><v2>{b}</v2><v3>{c}</v3></triangle>\n' for a, b, c in T)
       + '</volume></mesh></object>\n</amf>\n')
with open("tetra_meter.amf", "w") as f:
    f.write(amf)
