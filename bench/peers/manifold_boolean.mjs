// The Manifold peer for the boolean benchmark (bench/boolean_compare.sh):
// Manifold's WebAssembly build (npm manifold-3d), driven by Node.
//   MANIFOLD_DIR=DIR node manifold_boolean.mjs A.stl B.stl ROUNDS
// (DIR: where `npm install manifold-3d` ran; default: beside this script)
// Reads two binary STL files (float32, as polyvol reads them), merges their
// corners into indexed meshes, builds a Manifold of each (not timed as the
// call), then times ROUNDS calls of A.intersect(B).volume() and prints one
// JSON line: {"volume": ..., "call_seconds": [...], "build_seconds": ...}.
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath, pathToFileURL } from 'node:url';

const dir = process.env.MANIFOLD_DIR ?? dirname(fileURLToPath(import.meta.url));
const { default: Module } = await import(pathToFileURL(join(dir, 'node_modules/manifold-3d/manifold.js')).href);

// Binary STL -> Manifold's MeshGL fields: 3 corners per facet, float32.
function readBinaryStl(path) {
  const buf = readFileSync(path);
  const n = buf.readUInt32LE(80);
  if (buf.length !== 84 + 50 * n) throw new Error(`${path}: not a binary STL of ${n} facets`);
  const vert = new Float32Array(9 * n);
  for (let i = 0; i < n; ++i) {
    const base = 84 + 50 * i + 12;  // skip the normal
    for (let k = 0; k < 9; ++k) vert[9 * i + k] = buf.readFloatLE(base + 4 * k);
  }
  const tri = new Uint32Array(3 * n);
  for (let i = 0; i < 3 * n; ++i) tri[i] = i;
  return { numProp: 3, vertProperties: vert, triVerts: tri };
}

const [a, b, roundsArg] = process.argv.slice(2);
const rounds = Number(roundsArg ?? 5);
const wasm = await Module();
wasm.setup();
const { Manifold, Mesh } = wasm;

const t0 = performance.now();
const solids = [a, b].map((path) => {
  const mesh = new Mesh(readBinaryStl(path));
  mesh.merge();  // weld equal corners: the indexed mesh Manifold requires
  const m = new Manifold(mesh);
  if (m.status() !== 'NoError') throw new Error(`${path}: Manifold status ${m.status()}`);
  return m;
});
const build = (performance.now() - t0) / 1000;

const calls = [];
let volume = 0;
for (let r = 0; r < rounds; ++r) {
  const t = performance.now();
  const result = solids[0].intersect(solids[1]);
  volume = result.volume();
  calls.push((performance.now() - t) / 1000);
  result.delete();
}
console.log(JSON.stringify({ volume, call_seconds: calls, build_seconds: build }));
