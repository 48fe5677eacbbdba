// The WebAssembly build gives the command line's bytes: for every corpus file
// the core reads, `volume`, `measure` and `check` --json (and `measure` with a
// density, units and the full self-crossing check) print the same text, the
// same exit code and the same messages as the native `polyvol` run in the
// file's directory.
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { test } from 'node:test';

import { zipSync } from 'fflate';

import { corpusDir as corpusRoot, corpusPath, loadPackage, manifest, runCli } from './environment.mjs';

const corpusDir = () => corpusRoot;

const { createPolyvol } = await loadPackage();
const polyvol = await createPolyvol();

const requests = [
  { command: 'volume', args: ['volume', '--json'], options: {} },
  { command: 'measure', args: ['measure', '--json'], options: {} },
  { command: 'check', args: ['check', '--json'], options: {} },
  {
    command: 'measure',
    args: ['measure', '--json', '--solid', '--density', '1.24g/cm3', '--units', 'mm', '--mass-unit', 'g'],
    options: { solid: true, density: '1.24g/cm3', units: 'mm', massUnit: 'g' },
  },
];

// The formats the WebAssembly build reads (gzip through fflate); 3MF and AMF
// are not read there yet (docs/web.md).
const direct = manifest.filter((e) => ['stl', 'obj', 'off', 'ply'].includes(e.format));

test('the corpus has files of every format the core reads', () => {
  assert.ok(direct.length > 100, `${direct.length} files`);
});

for (const entry of direct) {
  test(entry.path, () => {
    const file = corpusPath(entry);
    const name = path.basename(file);
    const data = readFileSync(file);
    for (const r of requests) {
      const native = runCli([...r.args, name], path.dirname(file));
      const wasm = polyvol.run(r.command, [{ name, data }], r.options);
      assert.equal(wasm.stdout, native.stdout, `${r.args.join(' ')}: stdout`);
      assert.equal(wasm.exitCode, native.code, `${r.args.join(' ')}: exit code`);
      assert.deepEqual(wasm.messages, native.messages, `${r.args.join(' ')}: messages`);
    }
  });
}

// The same request through the package and the command line, in a directory
// of its own holding `files` ({name: bytes}).
function both(args, command, options, files) {
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-npm-'));
  for (const [name, data] of Object.entries(files)) writeFileSync(path.join(dir, name), data);
  const names = Object.keys(files);
  const native = runCli([...args, ...names], dir);
  const wasm = polyvol.run(command, names.map((name) => ({ name, data: files[name] })), options);
  return { native, wasm };
}

test('a zip of meshes: each member measured, named ARCHIVE:MEMBER, as the command line does', () => {
  const pick = ['stl-models/unitCube.ascii.stl', 'geomview/dodec.off', 'libcgal-demo/sphere.ply'];
  const entries = Object.fromEntries(pick.map((p) => [`parts/${path.basename(p)}`, readFileSync(path.join(corpusDir(), 'meshes', p))]));
  entries['readme.txt'] = new TextEncoder().encode('not a mesh');
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'parts.zip': zipSync(entries) });
  assert.equal(wasm.stdout, native.stdout);
  assert.equal(wasm.exitCode, native.code);
  const results = JSON.parse(wasm.stdout);
  assert.deepEqual(results.map((r) => r.file), pick.map((p) => `parts.zip:parts/${path.basename(p)}`));
  assert.equal(results[0].volume, 1);
});

test('a zip whose entry would expand past the decompression limit is refused, unread', () => {
  const big = new Uint8Array(40 << 20);  // 40 MiB of zeros: a 40 KB archive, whose limit is 16 MiB
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'bomb.zip': zipSync({ 'bomb.stl': big }) });
  assert.equal(native.code, 2);
  assert.equal(wasm.exitCode, 2);
  assert.match(wasm.messages.join('\n'), /limit/);
});

test("a file that is not what its name says: the command line's error, exit code 2", () => {
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'part.zip': new TextEncoder().encode('not a zip') });
  assert.equal(wasm.exitCode, native.code);
  assert.equal(wasm.exitCode, 2);
});
