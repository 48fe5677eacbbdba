"""Writes the unit test files of tests/cli/units_cli_test.cpp (run from this
directory with python3): the unit corner tetrahedron scaled by 2 (volume 4/3
in the file's unit) as a 3MF whose model says unit="inch", and as an AMF
whose root says unit="meter"."""
import zipfile

V = [(0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2)]
T = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]

model = ('<?xml version="1.0" encoding="UTF-8"?>\n'
         '<model unit="inch" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n'
         '<resources><object id="1" type="model"><mesh><vertices>\n'
         + "".join(f'<vertex x="{x}" y="{y}" z="{z}"/>\n' for x, y, z in V)
         + '</vertices><triangles>\n'
         + "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>\n' for a, b, c in T)
         + '</triangles></mesh></object></resources>\n<build><item objectid="1"/></build>\n</model>\n')
with zipfile.ZipFile("tetra_inch.3mf", "w", zipfile.ZIP_DEFLATED) as z:
    z.writestr("[Content_Types].xml",
               '<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
               '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
               '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>\n')
    z.writestr("_rels/.rels",
               '<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
               '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
               'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>\n')
    z.writestr("3D/3dmodel.model", model)

amf = ('<?xml version="1.0" encoding="UTF-8"?>\n<amf unit="meter">\n<object id="0"><mesh><vertices>\n'
       + "".join(f'<vertex><coordinates><x>{x}</x><y>{y}</y><z>{z}</z></coordinates></vertex>\n' for x, y, z in V)
       + '</vertices><volume>\n'
       + "".join(f'<triangle><v1>{a}</v1><v2>{b}</v2><v3>{c}</v3></triangle>\n' for a, b, c in T)
       + '</volume></mesh></object>\n</amf>\n')
with open("tetra_meter.amf", "w") as f:
    f.write(amf)
