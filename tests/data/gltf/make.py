"""Writes the glTF inputs of tests/cli/gltf_cli_test.cpp (run here with python3).

The 2-cube [0, 2]^3 (volume 8, area 24, centroid (1, 1, 1)), outward:
- cube.gltf + cube.bin: float positions, unsigned short indices, one node
  translated by (10, 0, 0);
- cube.glb: the same in one binary file, the node rotated 90 degrees about z
  and scaled by 2 (volume 64);
- fan_strip.gltf: buffers as a data: URI; the cube's faces as triangle fans
  (mode 6) and triangle strips (mode 5), no indices, beside a line primitive
  (skipped);
- quantized.gltf: positions as normalized unsigned shorts (65535 = 1) under
  a scale of 2 (KHR_mesh_quantization), and a sparse accessor that moves
  nothing away from the cube (it rewrites two corners with their own values);
- draco.gltf: requires KHR_draco_mesh_compression (refused by name);
- escape.gltf: a buffer outside the file's directory, ../weld/box.obj (refused).
"""
import base64
import json
import math
import struct

V = [(x, y, z) for z in (0, 2) for y in (0, 2) for x in (0, 2)]  # corner i: bit 0 x, bit 1 y, bit 2 z
QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
TRIS = [t for a, b, c, d in QUADS for t in ((a, b, c), (a, c, d))]


def pack(fmt, rows):
    return b"".join(struct.pack(fmt, *r) for r in rows)


def document(buffers, views, accessors, meshes, nodes, extra=None):
    d = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}],
         "nodes": nodes, "meshes": meshes, "accessors": accessors, "bufferViews": views, "buffers": buffers}
    d.update(extra or {})
    return d


def cube_parts(uri=None):
    pos = pack("<3f", V)
    idx = pack("<3H", TRIS)
    data = pos + idx
    buffer = {"byteLength": len(data)}
    if uri:
        buffer["uri"] = uri
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
             {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                  "min": [0, 0, 0], "max": [2, 2, 2]},
                 {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]
    meshes = [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}]
    return data, [buffer], views, accessors, meshes


data, buffers, views, accessors, meshes = cube_parts("cube.bin")
open("cube.bin", "wb").write(data)
json.dump(document(buffers, views, accessors, meshes, [{"mesh": 0, "translation": [10, 0, 0]}]),
          open("cube.gltf", "w"), indent=1)

# glb: JSON chunk padded with spaces, BIN chunk padded with zeros
data, buffers, views, accessors, meshes = cube_parts()
s = math.sqrt(0.5)
doc = json.dumps(document(buffers, views, accessors, meshes,
                          [{"mesh": 0, "rotation": [0, 0, s, s], "scale": [2, 2, 2]}])).encode()
doc += b" " * (-len(doc) % 4)
data += b"\0" * (-len(data) % 4)
glb = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(doc) + 8 + len(data))
glb += struct.pack("<II", len(doc), 0x4E4F534A) + doc + struct.pack("<II", len(data), 0x004E4942) + data
open("cube.glb", "wb").write(glb)

# fans and strips, non-indexed, in a data: URI; one LINES primitive
fan_rows = []
strip_rows = []
prims = []
blobs = b""
accs = []
vws = []
for i, (a, b, c, d) in enumerate(QUADS):
    # the quad a b c d as a fan (a b c d: triangles a b c, a c d), or as a
    # strip (b c a d: b c a, then c d a with the strip's odd-triangle rule)
    rows = [V[a], V[b], V[c], V[d]] if i % 2 == 0 else [V[b], V[c], V[a], V[d]]
    blob = pack("<3f", rows)
    vws.append({"buffer": 0, "byteOffset": len(blobs), "byteLength": len(blob)})
    accs.append({"bufferView": len(vws) - 1, "componentType": 5126, "count": 4, "type": "VEC3"})
    prims.append({"attributes": {"POSITION": len(accs) - 1}, "mode": 6 if i % 2 == 0 else 5})
    blobs += blob
prims.append({"attributes": {"POSITION": 0}, "mode": 1})
uri = "data:application/octet-stream;base64," + base64.b64encode(blobs).decode()
json.dump(document([{"byteLength": len(blobs), "uri": uri}], vws, accs, [{"primitives": prims}], [{"mesh": 0}]),
          open("fan_strip.gltf", "w"), indent=1)

# quantized: 65535 = 1.0, scale 2; a sparse accessor rewriting corners 0 and 7 with their own values
q = pack("<3H", [(65535 * (x // 2), 65535 * (y // 2), 65535 * (z // 2)) for x, y, z in V])
q += b"\0\0" * (-len(q) // 2 % 2)
idx = pack("<3H", TRIS)
sp_idx = struct.pack("<2H", 0, 7)
sp_val = pack("<3H", [(0, 0, 0), (65535, 65535, 65535)])
blob = q + idx + sp_idx + sp_val
qviews = [{"buffer": 0, "byteOffset": 0, "byteLength": len(q)},
          {"buffer": 0, "byteOffset": len(q), "byteLength": len(idx)},
          {"buffer": 0, "byteOffset": len(q) + len(idx), "byteLength": len(sp_idx)},
          {"buffer": 0, "byteOffset": len(q) + len(idx) + len(sp_idx), "byteLength": len(sp_val)}]
qacc = [{"bufferView": 0, "componentType": 5123, "normalized": True, "count": 8, "type": "VEC3",
         "sparse": {"count": 2, "indices": {"bufferView": 2, "componentType": 5123}, "values": {"bufferView": 3}}},
        {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]
uri = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
json.dump(document([{"byteLength": len(blob), "uri": uri}], qviews, qacc,
                   [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}], [{"mesh": 0, "scale": [2, 2, 2]}],
                   {"extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"]}),
          open("quantized.gltf", "w"), indent=1)

data, buffers, views, accessors, meshes = cube_parts("cube.bin")
json.dump(document(buffers, views, accessors, meshes, [{"mesh": 0}],
                   {"extensionsUsed": ["KHR_draco_mesh_compression"],
                    "extensionsRequired": ["KHR_draco_mesh_compression"]}), open("draco.gltf", "w"), indent=1)
data, buffers, views, accessors, meshes = cube_parts("../weld/box.obj")
json.dump(document(buffers, views, accessors, meshes, [{"mesh": 0}]), open("escape.gltf", "w"), indent=1)
