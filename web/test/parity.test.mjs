// The WebAssembly build gives the command line's bytes: for every corpus file
// the core reads, `volume`, `measure` and `check` --json (and `measure` with a
// density, units and the full self-crossing check) print the same text, the
// same exit code and the same messages as the native `polyvol` run in the
// file's directory.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { test } from 'node:test';

import { gzipSync, zipSync } from 'fflate';

import { corpusDir as corpusRoot, corpusPath, loadPackage, manifest, runCli } from './environment.mjs';

const corpusDir = () => corpusRoot;

const { createPolyvol } = await loadPackage();
const polyvol = await createPolyvol();

const requests = [
  { command: 'volume', args: ['volume', '--json'], options: {} },
  { command: 'measure', args: ['measure', '--json'], options: {} },
  { command: 'check', args: ['check', '--json'], options: {} },
  { command: 'volume', args: ['volume', '--stream', '--json'], options: { stream: true } },
  { command: 'volume', args: ['volume', '--stream', '--volume-only', '--json'], options: { stream: true, volumeOnly: true } },
  {
    command: 'measure',
    args: ['measure', '--json', '--solid', '--density', '1.24g/cm3', '--units', 'mm', '--mass-unit', 'g'],
    options: { solid: true, density: '1.24g/cm3', units: 'mm', massUnit: 'g' },
  },
];

// Every corpus file (gzip and zip through fflate, 3MF's and AMF's XML through parse-xml).
const direct = manifest;

test('the corpus has files of every format the core reads', () => {
  const formats = new Set(direct.map((e) => e.format));
  for (const f of ['stl', 'obj', 'off', 'ply', '3mf', 'amf']) assert.ok(formats.has(f), f);
  assert.ok(direct.length > 130, `${direct.length} files`);
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
      if (r.command === 'measure') {
        const csv = runCli([...r.args.filter((a) => a !== '--json'), '--csv', name], path.dirname(file));
        assert.equal(wasm.csv, csv.stdout, `${r.args.join(' ')} --csv`);
      }
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
  assert.match(wasm.messages.join('\n'), /decompression limit/);
  assert.deepEqual(wasm.messages, native.messages);
});

test("a zip entry whose bytes are not its CRC-32's, or fewer than its record says: the command line's words", () => {
  const obj = readFileSync(path.join(corpusDir(), 'meshes', 'geomview/dodec.off'));
  const stored = zipSync({ 'dodec.off': [obj, { level: 0 }] });
  const at = stored.indexOf(obj[0], 30 + 'dodec.off'.length);  // the entry's first byte, stored as it is
  const corrupt = new Uint8Array(stored);
  corrupt[at + 100] ^= 0x20;
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'parts.zip': corrupt });
  assert.equal(native.code, 2);
  assert.match(native.messages.join('\n'), /CRC mismatch/);
  assert.equal(wasm.exitCode, native.code);
  assert.deepEqual(wasm.messages, native.messages);
  assert.equal(wasm.stdout, native.stdout);
});

test('a gzip bomb is stopped at the decompression limit, not after it went off', () => {
  const bomb = gzipSync(new Uint8Array(64 << 20), { level: 9 });  // 64 MiB of zeros in about 64 KB: limit 16 MiB
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'bomb.stl.gz': bomb });
  assert.equal(native.code, 2);
  assert.equal(wasm.exitCode, 2);
  assert.match(wasm.messages.join('\n'), /decompression limit/);
  assert.deepEqual(wasm.messages, native.messages);
});

// A tar of `files` ({path: bytes}), made by GNU tar (ustar, and a pax header
// for a long name).
function tarOf(files) {
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-tar-'));
  for (const [name, data] of Object.entries(files)) {
    mkdirSync(path.dirname(path.join(dir, name)), { recursive: true });
    writeFileSync(path.join(dir, name), data);
  }
  const r = spawnSync('tar', ['--format=pax', '-cf', '-', ...Object.keys(files)], { cwd: dir, maxBuffer: 1 << 28 });
  assert.equal(r.status, 0, String(r.stderr));
  return r.stdout;
}

test('tar archives, plain and gzip-compressed: each mesh member measured, named ARCHIVE:MEMBER, as the command line does', () => {
  const pick = ['stl-models/unitCube.ascii.stl', 'geomview/dodec.off', 'libcgal-demo/sphere.ply'];
  const files = Object.fromEntries(pick.map((p) => [`parts/${path.basename(p)}`, readFileSync(path.join(corpusDir(), 'meshes', p))]));
  files['parts/notes.txt'] = new TextEncoder().encode('not a mesh');
  files[`parts/${'a-long-directory-name-'.repeat(6)}/cube.stl`] = files['parts/unitCube.ascii.stl'];
  const tar = tarOf(files);
  for (const [name, data] of [['parts.tar', tar], ['parts.tar.gz', gzipSync(tar)], ['parts.tgz', gzipSync(tar)]]) {
    for (const r of requests) {
      const { native, wasm } = both(r.args, r.command, r.options, { [name]: data });
      assert.equal(wasm.stdout, native.stdout, `${name}: ${r.args.join(' ')}`);
      assert.equal(wasm.exitCode, native.code);
      assert.deepEqual(wasm.messages, native.messages);
    }
    const { results } = polyvol.measure(data, name);
    assert.equal(results.length, 4);
    assert.equal(results[0].file, `${name}:parts/unitCube.ascii.stl`);
  }
  // A tar whose header checksum is wrong: the command line's words.
  const bad = new Uint8Array(tar);
  bad[148] ^= 1;
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'bad.tar': bad });
  assert.equal(wasm.exitCode, native.code);
  assert.deepEqual(wasm.messages, native.messages);
});

test('a bzip2-compressed file: refused by name with exit code 2 (the command line reads it)', () => {
  const r = spawnSync('bzip2', ['-c'], { input: readFileSync(path.join(corpusDir(), 'meshes', 'geomview/dodec.off')) });
  assert.equal(r.status, 0);
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'dodec.off.bz2': r.stdout });
  assert.equal(native.code, 0);
  assert.equal(wasm.exitCode, 2);
  assert.deepEqual(wasm.messages, ["polyvol: dodec.off.bz2: bzip2-compressed: not read by polyvol's WebAssembly build"]);
});

test("a file that is not what its name says: the command line's error, exit code 2", () => {
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'part.zip': new TextEncoder().encode('not a zip') });
  assert.equal(wasm.exitCode, native.code);
  assert.equal(wasm.exitCode, 2);
});

// A tetrahedron as AMF, in inches, with `z` as the last vertex's z and `before`
// ahead of the root element.
function amf(z, before = '') {
  const v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, z]];
  const vertex = ([a, b, c]) => `<vertex><coordinates><x>${a}</x><y>${b}</y><z>${c}</z></coordinates></vertex>`;
  const tri = ([a, b, c]) => `<triangle><v1>${a}</v1><v2>${b}</v2><v3>${c}</v3></triangle>`;
  return `<?xml version="1.0" encoding="UTF-8"?>\n${before}<amf unit="inch">\n<object id="0"><mesh>\n<vertices>\n` +
    v.map(vertex).join('\n') + '\n</vertices>\n<volume>\n' + [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]].map(tri).join('\n') +
    '\n</volume>\n</mesh></object>\n</amf>\n';
}
const utf16le = (text) => {
  const out = new Uint8Array(2 + 2 * text.length);
  out[0] = 0xff; out[1] = 0xfe;
  for (let i = 0; i < text.length; ++i) { out[2 + 2 * i] = text.charCodeAt(i) & 0xff; out[3 + 2 * i] = text.charCodeAt(i) >> 8; }
  return out;
};

test("3MF's and AMF's XML read as the command line reads it: encodings, line ends, CDATA, entities; a bad value's line", () => {
  const utf8 = (t) => new TextEncoder().encode(t);
  const files = {
    'plain.amf': utf8(amf('1')),
    'crlf.amf': utf8(amf('1').replace(/\n/g, '\r\n')),
    'bom.amf': new Uint8Array([0xef, 0xbb, 0xbf, ...utf8(amf('1'))]),
    'utf16.amf': utf16le(amf('1').replace('UTF-8', 'UTF-16')),
    'cdata.amf': utf8(amf('<![CDATA[ 2 ]]>')),
    'entity.amf': utf8(amf('&#51;')),
    'bad-number.amf': utf8(amf('abc', '<!-- ünïcödé 日本 𝄞 -->\n<!-- two lines -->\n')),
    'bad-number-crlf.amf': utf8(amf('1e999', '<!-- é -->\n').replace(/\n/g, '\r\n')),
    'bad-number-utf16.amf': utf16le(amf('x').replace('UTF-8', 'UTF-16')),
    // A number split by a comment: pugixml's first text node, "1".
    'comment.amf': utf8(amf('1<!-- a comment -->2')),
    // An error at the start of a line after a byte-order mark: the command line's line.
    'bom-bad.amf': new Uint8Array([0xef, 0xbb, 0xbf, ...utf8(amf('1').replace(/<vertex><coordinates><x>0<\/x><y>0<\/y><z>0<\/z><\/coordinates><\/vertex>/, '<vertex></vertex>'))]),
  };
  const { native, wasm } = both(['measure', '--json', '--units', 'mm'], 'measure', { units: 'mm' }, files);
  assert.equal(wasm.stdout, native.stdout);
  assert.equal(wasm.exitCode, native.code);
  assert.deepEqual(wasm.messages, native.messages);
  const r = Object.fromEntries(JSON.parse(wasm.stdout).map((e) => [e.file, e]));
  assert.equal(r['cdata.amf'].volume, 2 / 6);
  assert.equal(r['entity.amf'].volume, 3 / 6);
  assert.equal(r['utf16.amf'].volume, 1 / 6);
  assert.equal(r['comment.amf'].volume, 1 / 6);
  assert.match(r['bom-bad.amf'].error, /^bom-bad\.amf:5: <vertex> without <coordinates>/);
  assert.match(r['bad-number.amf'].error, /^bad-number\.amf:10: bad number 'abc' in <z>/);
});

test('malformed XML: exit code 2 and the byte where the parser stopped, in its own words', () => {
  const text = amf('1').replace('</vertices>', '');
  const { native, wasm } = both(['measure', '--json'], 'measure', {}, { 'broken.amf': new TextEncoder().encode(text) });
  assert.equal(native.code, 2);
  assert.equal(wasm.exitCode, 2);
  const at = (m) => Number(/byte (\d+): XML parse error/.exec(m)[1]);
  const [n, w] = [at(native.messages.join('\n')), at(wasm.messages.join('\n'))];
  assert.ok(Math.abs(n - w) < 20, `byte ${w} here, ${n} on the command line`);
});

// `overlap --json` less its "seconds" (the time taken).
const untimed = (text) => text.replace(/\n\s*"seconds": [^\n]*\n/, '\n').replace(/,\n}/, '\n}');

test('overlap: closed corpus meshes in pairs, and a mesh with itself, as the command line', () => {
  const closed = manifest.filter((e) => e.topology?.closed && e.counts.triangles < 20000 && direct.includes(e));
  assert.ok(closed.length > 40, `${closed.length} closed meshes`);
  const pairs = closed.slice(0, 20).map((e, i) => [e, closed[(i + 1) % closed.length]]);
  pairs.push([closed[0], closed[0]], [closed[5], closed[5]]);
  for (const [ea, eb] of pairs) {
    const files = { [`a-${path.basename(ea.path)}`]: readFileSync(corpusPath(ea)), [`b-${path.basename(eb.path)}`]: readFileSync(corpusPath(eb)) };
    const { native, wasm } = both(['overlap', '--json'], 'overlap', {}, files);
    assert.equal(untimed(wasm.stdout), untimed(native.stdout), `${ea.path} with ${eb.path}`);
    assert.equal(wasm.exitCode, native.code);
    assert.deepEqual(wasm.messages, native.messages);
  }
});

test('overlap: two overlapping cubes in mm, figures in cm; an open operand refused with the command line\'s words', () => {
  const cube = (o) => {
    const v = [];
    for (const z of [0, 2]) for (const y of [0, 2]) for (const x of [0, 2]) v.push(`v ${x + o} ${y + o} ${z + o}`);
    const f = [[1, 3, 4, 2], [5, 6, 8, 7], [1, 2, 6, 5], [3, 7, 8, 4], [1, 5, 7, 3], [2, 4, 8, 6]];
    return [...v, ...f.map((q) => 'f ' + q.join(' '))].join('\n') + '\n';
  };
  const files = { 'a.obj': cube(0), 'b.obj': cube(1) };
  const { native, wasm } = both(['overlap', '--json', '--units', 'mm', '--to', 'cm'], 'overlap', { units: 'mm', to: 'cm' }, files);
  assert.equal(untimed(wasm.stdout), untimed(native.stdout));
  const r = JSON.parse(wasm.stdout);
  assert.equal(r.unit, 'cm');
  assert.ok(Math.abs(r.intersection - 0.001) <= r.volume_error_bound);
  const open = { 'a.obj': cube(0), 'b.obj': cube(1).split('\n').slice(0, -2).join('\n') + '\n' };
  const refused = both(['overlap', '--json'], 'overlap', {}, open);
  assert.equal(refused.wasm.exitCode, 3);
  assert.equal(refused.wasm.exitCode, refused.native.code);
  assert.deepEqual(refused.wasm.messages, refused.native.messages);
  assert.equal(refused.wasm.stdout, '');
});

test('the top-level calls (import { measure, check, volume, overlap } from the package) answer as the command line', async () => {
  const pkg = await loadPackage();
  const file = corpusPath(manifest.find((e) => e.path.endsWith('unitCube.ascii.stl')));
  const data = readFileSync(file);
  for (const command of ['volume', 'measure', 'check']) {
    const r = await pkg[command](data, 'unitCube.ascii.stl');
    const native = runCli([command, '--json', 'unitCube.ascii.stl'], path.dirname(file));
    assert.equal(r.json, native.stdout);
    assert.equal(r.results[0].file, 'unitCube.ascii.stl');
  }
  const o = await pkg.overlap(data, 'a.stl', data, 'b.stl');
  assert.equal(o.exitCode, 0);
  assert.equal(o.result.intersection, 1);
  const bad = await pkg.measure(new Uint8Array([1, 2, 3]), 'x.stl');
  assert.equal(bad.exitCode, 2);
  assert.match(bad.results[0].error, /x\.stl/);
});

test('onProgress: each file through its stages, a streamed STL by whole percents up to 1', () => {
  const cube = readFileSync(path.join(corpusDir(), 'meshes', 'stl-models/unitCube.ascii.stl'));
  const seen = [];
  const r = polyvol.measure(cube, 'cube.stl', { onProgress: (p) => seen.push(p) });
  assert.equal(r.exitCode, 0);
  assert.deepEqual(seen, [
    { file: 'cube.stl', stage: 'reading', fraction: 0 }, { file: 'cube.stl', stage: 'checking', fraction: 0 },
    { file: 'cube.stl', stage: 'measuring', fraction: 0 }, { file: 'cube.stl', stage: 'measuring', fraction: 1 }]);
  // A binary STL of 100,000 triangles (windows of about 4,000), streamed: pass 1 read by percents.
  const n = 100000;
  const stl = new Uint8Array(84 + 50 * n);
  const view = new DataView(stl.buffer);
  view.setUint32(80, n, true);
  for (let t = 0; t < n; ++t) {  // n/2 pairs: a triangle and its reverse (closed, volume 0)
    const at = 84 + 50 * t + 12, k = t >> 1, flip = t & 1;
    const pts = [[k, 0, 0], [k, 1, 0], [k, 0, 1]];
    if (flip) pts.reverse();
    pts.flat().forEach((x, i) => view.setFloat32(at + 4 * i, x, true));
  }
  seen.length = 0;
  const s = polyvol.volume(stl, 'pairs.stl', { stream: true, onProgress: (p) => seen.push(p) });
  assert.equal(s.exitCode, 0, s.messages.join('\n'));
  assert.ok(seen.length > 20, `${seen.length} calls`);
  assert.deepEqual(seen[0], { file: 'pairs.stl', stage: 'reading', fraction: 0 });
  assert.deepEqual(seen.at(-1), { file: 'pairs.stl', stage: 'measuring', fraction: 1 });
  assert.equal(seen.filter((p) => p.stage === 'reading' && p.fraction === 1).length, 1);
  // Never back within a stage; reading (pass 1), then measuring (passes 2 and 3: the moments cancel here).
  const order = ['reading', 'checking', 'measuring'];
  for (let i = 1; i < seen.length; ++i) {
    assert.ok(order.indexOf(seen[i].stage) >= order.indexOf(seen[i - 1].stage), JSON.stringify(seen.slice(i - 1, i + 1)));
    if (seen[i].stage === seen[i - 1].stage) assert.ok(seen[i].fraction >= seen[i - 1].fraction, JSON.stringify(seen.slice(i - 1, i + 1)));
  }
  assert.ok(seen.some((p) => p.stage === 'measuring' && p.fraction > 0 && p.fraction < 1));
});

test('a Blob is read in a worker only (FileReaderSync): elsewhere a clear TypeError, the module still usable', () => {
  const cube = readFileSync(path.join(corpusDir(), 'meshes', 'stl-models/unitCube.ascii.stl'));
  assert.throws(() => polyvol.volume(new Blob([cube]), 'cube.stl'), /read in a worker \(FileReaderSync\)/);
  assert.equal(polyvol.volume(cube, 'cube.stl').results[0].volume, 1);
});
