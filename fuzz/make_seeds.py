#!/usr/bin/env python3
"""Writes fuzz/seeds/<target>/: small generated inputs for every fuzz target,
and copies of small corpus meshes (MIT, BSD-3-clause and CC0 files only; see
seeds/README.md). Run from the repository root; needs qconvex (qhull-bin).
    python3 fuzz/make_seeds.py [CORPUS_DIR]"""
import gzip, io, os, shutil, struct, subprocess, sys, zipfile

CORPUS = (sys.argv[1] if len(sys.argv) > 1 else '../shared/corpus') + '/meshes/'
SEEDS = 'fuzz/seeds/'


def put(target, name, data):
    os.makedirs(SEEDS + target, exist_ok=True)
    with open(SEEDS + target + '/' + name, 'wb' if isinstance(data, bytes) else 'w') as f:
        f.write(data)


def copy(target, rel):
    os.makedirs(SEEDS + target, exist_ok=True)
    shutil.copy(CORPUS + rel, SEEDS + target + '/' + os.path.basename(rel))


def zipped64(entries):
    """A zip whose headers all use ZIP64 (0xFFFFFFFF sizes and offsets, the values in extra field 1)."""
    import zlib
    out, central = bytearray(), bytearray()
    for name, text in entries:
        data, raw = text.encode(), None
        c = zlib.compressobj(9, zlib.DEFLATED, -15)
        raw = c.compress(data) + c.flush()
        crc, nb, off = zlib.crc32(data), name.encode(), len(out)
        out += struct.pack('<IHHHIIIIHH', 0x04034b50, 45, 0, 8, 0, crc, 0xFFFFFFFF, 0xFFFFFFFF, len(nb), 20) + nb
        out += struct.pack('<HHQQ', 1, 16, len(data), len(raw)) + raw
        central += struct.pack('<IHHHHIIIIHHHHHII', 0x02014b50, 45, 45, 0, 8, 0, crc, 0xFFFFFFFF, 0xFFFFFFFF,
                               len(nb), 28, 0, 0, 0, 0, 0xFFFFFFFF) + nb
        central += struct.pack('<HHQQQ', 1, 24, len(data), len(raw), off)
    cd = len(out)
    out += central
    end64 = len(out)
    out += struct.pack('<IQHHIIQQQQ', 0x06064b50, 44, 45, 45, 0, 0, len(entries), len(entries), len(central), cd)
    out += struct.pack('<IIQI', 0x07064b50, 0, end64, 1)
    out += struct.pack('<IHHHHIIH', 0x06054b50, 0, 0, 0xFFFF, 0xFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0)
    return bytes(out)


def zipped(entries):
    bio = io.BytesIO()
    with zipfile.ZipFile(bio, 'w', zipfile.ZIP_DEFLATED) as z:
        for name, data in entries:
            z.writestr(name, data)
    return bio.getvalue()


CORPUS_SEEDS = {
    'stl': ['stl-models/triangle.bin.stl', 'stl-models/tetrahedron.min.ascii.stl', 'stl-models/missingFace.ascii.stl',
            'stl-models/incorrectFaceCounter.bin.stl', 'assimp-testmodels/triangle_with_two_solids.stl',
            'stl-models/faceless.ascii.stl'],
    'obj': ['assimp-testmodels/box.obj', 'assimp-testmodels/testmixed.obj', 'assimp-testmodels/malformed.obj',
            'assimp-testmodels/regr_3429812.obj', 'assimp-testmodels/cube_with_vertexcolors.obj'],
    'off': ['libcgal-demo/tetrahedron.off', 'libcgal-demo/cube-shuffled.off', 'libcgal-demo/mesh_with_colors.off',
            'libcgal-demo/prim.off', 'assimp-testmodels/Cube.off', 'libcgal-demo/quad.off'],
    'ply': ['assimp-testmodels/cube.ply', 'assimp-testmodels/cube_binary.ply', 'assimp-testmodels/float-color.ply'],
}
for target, files in CORPUS_SEEDS.items():
    for rel in files:
        copy(target, rel)

# The unit tetrahedron, outward, in every format.
V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
obj = ''.join('v %g %g %g\n' % v for v in V) + ''.join('f %d %d %d\n' % tuple(i + 1 for i in f) for f in F)
put('obj', 'tet.obj', obj)
put('obj', 'quads.obj', 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\n'
                        'f -1 -2 -3\ng part\ns off\nusemtl m\n')


def ply_binary(big_endian):
    order = '>' if big_endian else '<'
    header = ('ply\nformat %s 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n'
              'element face 4\nproperty list uchar int vertex_indices\nend_header\n'
              % ('binary_big_endian' if big_endian else 'binary_little_endian'))
    body = b''.join(struct.pack(order + 'fff', *v) for v in V) + b''.join(struct.pack(order + 'Biii', 3, *f) for f in F)
    return header.encode() + body


put('ply', 'tet_le.ply', ply_binary(False))
put('ply', 'tet_be.ply', ply_binary(True))
put('ply', 'tet_ascii.ply', 'ply\nformat ascii 1.0\ncomment c\nelement vertex 4\nproperty double x\nproperty double y\n'
                            'property double z\nelement face 4\nproperty list uchar uint vertex_indices\nelement edge 1\n'
                            'property int a\nend_header\n' + ''.join('%g %g %g\n' % v for v in V)
                            + ''.join('3 %d %d %d\n' % f for f in F) + '7\n')
off = 'OFF\n4 4 6\n' + ''.join('%g %g %g\n' % v for v in V) + ''.join('3 %d %d %d\n' % f for f in F)
put('off', 'tet.off', off)
put('stl', 'tet_ascii.stl', 'solid t\n' + ''.join(
    'facet normal 0 0 0\nouter loop\n' + ''.join('vertex %g %g %g\n' % V[i] for i in f) + 'endloop\nendfacet\n'
    for f in F) + 'endsolid t\n')
stl_bin = b'\0' * 80 + struct.pack('<I', 4) + b''.join(
    struct.pack('<3f', 0, 0, 0) + b''.join(struct.pack('<3f', *V[i]) for i in f) + b'\0\0' for f in F)
put('stl', 'tet_bin.stl', stl_bin)
model = ('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" '
         'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>'
         '<object id="1" type="model"><mesh><vertices>' + ''.join('<vertex x="%g" y="%g" z="%g"/>' % v for v in V)
         + '</vertices><triangles>' + ''.join('<triangle v1="%d" v2="%d" v3="%d"/>' % f for f in F)
         + '</triangles></mesh></object><object id="2" type="model"><components>'
         '<component objectid="1" transform="1 0 0 0 1 0 0 0 1 2 0 0"/></components></object></resources>'
         '<build><item objectid="1"/><item objectid="2" transform="0 1 0 -1 0 0 0 0 1 0 0 5"/></build></model>')
put('3mf', 'tet.3mf', zipped([('[Content_Types].xml', '<?xml version="1.0"?><Types/>'), ('3D/3dmodel.model', model)]))
put('3mf', 'tet_stored.3mf', zipped([('3D/3dmodel.model', model)]))
put('3mf', 'tet_zip64.3mf', zipped64([('3D/3dmodel.model', model)]))
amf = ('<?xml version="1.0"?>\n<amf unit="millimeter"><object id="0"><mesh><vertices>'
       + ''.join('<vertex><coordinates><x>%g</x><y>%g</y><z>%g</z></coordinates></vertex>' % v for v in V)
       + '</vertices><volume>' + ''.join('<triangle><v1>%d</v1><v2>%d</v2><v3>%d</v3></triangle>' % f for f in F)
       + '</volume></mesh></object><constellation id="1"><instance objectid="0"><deltax>1</deltax><rz>30</rz>'
       '</instance></constellation></amf>\n')
put('amf', 'tet.amf', amf)
put('amf', 'tet_zipped.amf', zipped([('tet.amf', amf)]))
put('gzip', 'tet.obj.gz', gzip.compress(obj.encode()))
put('gzip', 'tet.stl.gz', gzip.compress(stl_bin))
put('gzip', 'two_members.off.gz', gzip.compress(off[:20].encode()) + gzip.compress(off[20:].encode()))
put('gzip', 'nested.ply.gz', gzip.compress(gzip.compress(ply_binary(False))))
chain = '3 4 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 2 1\n0 1 3\n0 3 2\n1 2 3\n'
put('chain', 'tet.chain', '# the unit tetrahedron\n' + chain)
put('chain', 'square.chain', '2 4 4\n0 0\n1 0\n1 1\n0 1\n0 1\n1 2\n2 3\n3 0\n')
put('chain', 'tet.chain.gz', gzip.compress(chain.encode()))
points4 = '4\n7\n' + ''.join('%g %g %g %g\n' % p for p in
                             [(0, 0, 0, 0), (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1),
                              (0.2, 0.2, 0.2, 0.2), (1, 1, 1, 1)])
put('qhull', 'simplex4.txt', subprocess.run(['qconvex', 'o', 'Qt'], input=points4, capture_output=True,
                                            text=True, check=True).stdout)
cube = '3\n8\n' + ''.join('%d %d %d\n' % (i & 1, i >> 1 & 1, i >> 2 & 1) for i in range(8))
put('qhull', 'cube3.txt', subprocess.run(['qconvex', 'o'], input=cube, capture_output=True, text=True,
                                         check=True).stdout)
put('polygons', 'holes.txt', '# a square with a square hole: area 64\n0 0 10 0 10 10 0 10\n2 2 2 8 8 8 8 2\n')
put('polygons', 'tri.txt', '0 0 1 0 0 1\r\n\n# c\n5 5 6 5 6 6 5 6\n')
# A shell crossing itself (two spheres joined by a tube through both), for solid_volume's within_shells.
sys.path.insert(0, 'tests/data/self_crossing')
import make as self_crossing  # noqa: E402
put('pipeline', 'self_crossing.obj', self_crossing.obj_text(*self_crossing.joined(3, 3)[0]))
# The whole path: a few of each format; the grid's inputs start with 3 bytes that choose the grid.
for path in ['obj/tet.obj', 'off/cube-shuffled.off', 'stl/tet_bin.stl', 'ply/tet_le.ply', '3mf/tet.3mf', 'obj/box.obj']:
    with open(SEEDS + path, 'rb') as f:
        data = f.read()
    put('pipeline', os.path.basename(path), data)
    put('grid', os.path.basename(path), b'\x05\x01\x10' + data)


# Corner-point grids: 3×2×2 cells, an inactive cell, repeats and comments; one
# with a fault on leaning pillars; one layer cake in FIELD units.
def grdecl(nx, ny, nz, throw, lean, head):
    coord = ' '.join('%r %r 1000 %r %r 1100' % (10.0 * i, 20.0 * j, 10.0 * i + lean * i, 20.0 * j)
                     for j in range(ny + 1) for i in range(nx + 1))
    z = ' '.join('2*%r' % (1000.0 + 5 * (k + c) + (throw if i >= 2 else 0.0))
                 for k in range(nz) for c in range(2) for j in range(ny) for b in range(2) for i in range(nx))
    act = ' '.join('0' if n == 1 else '1' for n in range(nx * ny * nz))
    return '%s-- a seed\nSPECGRID\n%d %d %d 1 F /\nCOORD\n%s /\nZCORN\n%s /\nACTNUM\n%s /\nPORO\n 3*0.2 /\n' % (
        head, nx, ny, nz, coord, z, act)


put('grdecl', 'inactive.grdecl', grdecl(3, 2, 2, 0.0, 0.0, "GRIDUNIT\n'METRES  ' /\n"))
put('grdecl', 'fault.grdecl', grdecl(3, 2, 2, 2.5, 1.5, 'METRIC\nMAPAXES\n 0 1 0 0 1 0 /\n'))
put('grdecl', 'field.grdecl', grdecl(2, 1, 3, 0.0, 0.0, 'FIELD\nECHO\n'))
