// The page in a real browser (Debian's chromium, headless, driven by
// puppeteer-core): files chosen on its file input are measured in its worker,
// and the card it shows holds the command line's JSON byte for byte, with the
// same words for a file that is not a solid; a broken file gives a clear
// message and the page goes on working; nothing is requested from any other
// origin. Screenshots go to build-wasm/screens for a person to look at.
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { zipSync } from 'fflate';
import puppeteer from 'puppeteer-core';

import { corpusDir, packageDir, root, runCli } from './environment.mjs';

const pageDir = path.join(path.dirname(packageDir), 'page');
const screens = path.join(path.dirname(packageDir), 'screens');
const chromium = process.env.POLYVOL_CHROMIUM ?? '/usr/bin/chromium';
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm' };
// The page's options as the command line's flags.
const flags = ['--density', '1.24g/cm3', '--units', 'mm', '--to', 'mm', '--mass-unit', 'g'];

let server, origin, browser, page;
const foreign = [];
const pageErrors = [];

before(async () => {
  mkdirSync(screens, { recursive: true });
  server = createServer((req, res) => {
    const p = path.join(pageDir, decodeURIComponent(new URL(req.url, 'http://x').pathname));
    try {
      const body = readFileSync(p.endsWith('/') ? path.join(p, 'index.html') : p);
      res.writeHead(200, { 'content-type': types[path.extname(p) || '.html'] ?? 'application/octet-stream' });
      res.end(body);
    } catch {
      res.writeHead(404).end();
    }
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  origin = `http://127.0.0.1:${server.address().port}`;
  browser = await puppeteer.launch({ executablePath: chromium, args: ['--headless=new', '--no-sandbox', '--disable-gpu'] });
  page = await browser.newPage();
  page.on('request', (r) => {
    if (!r.url().startsWith(origin) && !r.url().startsWith('data:') && !r.url().startsWith('blob:')) foreign.push(r.url());
  });
  page.on('pageerror', (e) => pageErrors.push(String(e)));
  await page.goto(`${origin}/index.html`, { waitUntil: 'load' });
});

after(async () => {
  await browser?.close();
  server?.close();
});

// Chooses files on the page's input and waits until it has shown them.
async function choose(...files) {
  for (const f of files) assert.ok(existsSync(f), `${f} exists`);
  const before = await page.evaluate(() => Number(document.body.dataset.done ?? 0));
  const input = await page.$('#files');
  await input.uploadFile(...files);
  await page.waitForFunction((n) => Number(document.body.dataset.done ?? 0) > n, { timeout: 120000 }, before);
}

async function card(name) {
  return page.$eval(`article[data-file="${name}"]`, (a) => ({ json: a.dataset.json, csv: a.dataset.csv, exitCode: Number(a.dataset.exitCode), text: a.innerText }));
}

function corpus(rel) {
  return path.join(corpusDir, 'meshes', rel);
}

for (const rel of ['stl-models/unitCube.ascii.stl', 'stl-models/bunny.bin.stl', 'geomview/dodec.off', 'libcgal-demo/sphere.ply']) {
  test(`a corpus file shows the command line's JSON: ${rel}`, async () => {
    const file = corpus(rel);
    const name = path.basename(file);
    await choose(file);
    const shown = await card(name);
    const native = runCli(['measure', '--json', ...flags, name], path.dirname(file));
    assert.equal(shown.json, native.stdout);
    assert.equal(shown.exitCode, native.code);
    assert.equal(shown.csv, runCli(['measure', '--csv', ...flags, name], path.dirname(file)).stdout);
    for (const m of native.messages) assert.ok(shown.text.includes(m.replace(/^polyvol: /, '')), `the page says: ${m}`);
    await page.screenshot({ path: path.join(screens, `${name}.png`), fullPage: true });
  });
}

test("the bundled examples and a 3MF in inches: the command line's JSON, in millimetres", async () => {
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-web-'));
  // A cube of one inch's side: 3D/3dmodel.model in a zip, as 3MF writers make it.
  const v = [];
  for (const z of [0, 1]) for (const y of [0, 1]) for (const x of [0, 1]) v.push(`<vertex x="${x}" y="${y}" z="${z}"/>`);
  const t = [[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4], [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]]
    .map(([a, b, c]) => `<triangle v1="${a}" v2="${b}" v3="${c}"/>`);
  const model = '<?xml version="1.0" encoding="UTF-8"?>\n<model unit="inch" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n' +
    `<resources><object id="1" type="model"><mesh><vertices>${v.join('\n')}</vertices>\n<triangles>${t.join('\n')}</triangles></mesh></object></resources>\n` +
    '<build><item objectid="1"/></build>\n</model>\n';
  const rels = '<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">' +
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>';
  const text = (x) => new TextEncoder().encode(x);
  writeFileSync(path.join(dir, 'inch-cube.3mf'), zipSync({ '_rels/.rels': text(rels), '3D/3dmodel.model': text(model) }));
  const bundled = path.join(root, 'examples');
  await choose(path.join(dir, 'inch-cube.3mf'), path.join(bundled, 'two_parts.3mf'), path.join(bundled, 'l_bracket.obj'));
  // The page's units are for files that state none: the command line's --units is left out for a 3MF.
  const stated = flags.filter((f, i) => f !== '--units' && flags[i - 1] !== '--units');
  const cases = [
    [path.join(dir, 'inch-cube.3mf'), stated],
    [path.join(bundled, 'two_parts.3mf'), stated],
    [path.join(bundled, 'l_bracket.obj'), flags],
  ];
  for (const [file, f] of cases) {
    const name = path.basename(file);
    const shown = await card(name);
    const native = runCli(['measure', '--json', ...f, name], path.dirname(file));
    assert.equal(shown.json, native.stdout, name);
    assert.equal(shown.exitCode, native.code, name);
  }
  const inch = JSON.parse((await card('inch-cube.3mf')).json)[0];
  assert.equal(inch.unit, 'mm');
  assert.equal(inch.volume, 16387.064);  // 25.4³ mm³, correctly rounded
  assert.match((await card('inch-cube.3mf')).text, /16387\.064 mm³/);
  assert.match((await card('inch-cube.3mf')).text, /Note: the file's unit is inch\./);
  await page.screenshot({ path: path.join(screens, 'examples-and-inch-cube.png'), fullPage: true });
});

test('an open mesh: the page says why there is no volume', async () => {
  const file = corpus('stl-models/bunny.bin.stl');
  const shown = await card(path.basename(file));
  assert.equal(shown.exitCode, 3);
  assert.match(shown.text, /not a closed surface/);
  assert.doesNotMatch(shown.text, /^Volume/m);
});

// Clicks a card's "View in 3D" and waits for the view.
async function view3d(name) {
  await page.evaluate(() => { delete document.getElementById('view').dataset.ready; });
  await page.$eval(`article[data-file="${name}"] button.view-3d`, (b) => b.click());
  await page.waitForFunction(() => document.getElementById('view').dataset.ready, { timeout: 120000 });
  return page.$eval('#view', (v) => ({ ...v.dataset, words: document.getElementById('view-words').textContent }));
}

test("the 3D view: an open mesh's boundary edges drawn over it, as many as check counts", async () => {
  const file = corpus('stl-models/bunny.bin.stl');
  const shown = await view3d(path.basename(file));
  const checked = JSON.parse(runCli(['check', '--json', path.basename(file)], path.dirname(file)).stdout)[0];
  assert.equal(Number(shown.triangles), checked.triangles);
  assert.equal(Number(shown.problemEdges), checked.boundary_edges);
  assert.match(shown.words, new RegExp(`${checked.boundary_edges} boundary edges \\(red\\)`));
  assert.doesNotMatch(shown.words, /No 3D view/);
  // Something was drawn: the canvas is not all one colour.
  const colours = await page.$eval('#view-canvas', (c) => {
    const probe = document.createElement('canvas');
    [probe.width, probe.height] = [c.width, c.height];
    const g = probe.getContext('2d');
    g.drawImage(c, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const seen = new Set();
    for (let i = 0; i < d.length; i += 4 * 97) seen.add(`${d[i]},${d[i + 1]},${d[i + 2]}`);
    return seen.size;
  });
  assert.ok(colours > 10, `${colours} colours on the canvas`);
  await page.screenshot({ path: path.join(screens, 'view-bunny.png'), fullPage: true });
});

test('two overlapping cubes in one file: the solid, counted once', async () => {
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-web-'));
  const cube = (o) => {
    const v = [];
    for (const z of [0, 2]) for (const y of [0, 2]) for (const x of [0, 2]) v.push(`v ${x + o} ${y + o} ${z + o}`);
    return v;
  };
  const faces = [[1, 3, 4, 2], [5, 6, 8, 7], [1, 2, 6, 5], [3, 7, 8, 4], [1, 5, 7, 3], [2, 4, 8, 6]];
  const f = (k) => faces.map((q) => 'f ' + q.map((i) => i + 8 * k).join(' '));
  const file = path.join(dir, 'two-cubes.obj');
  writeFileSync(file, [...cube(0), ...cube(1), ...f(0), ...f(1)].join('\n') + '\n');
  await choose(file);
  const shown = await card('two-cubes.obj');
  const native = runCli(['measure', '--json', ...flags, 'two-cubes.obj'], dir);
  assert.equal(shown.json, native.stdout);
  assert.equal(JSON.parse(shown.json)[0].volume, 15);
  assert.match(shown.text, /overlap/);
  const seen = await view3d('two-cubes.obj');
  assert.equal(seen.shells, 'solid solid');
  assert.equal(Number(seen.problemEdges), 0);
  assert.match(seen.words, /2 shells: 2 solid; 2 crossing another shell/);
  await page.screenshot({ path: path.join(screens, 'two-cubes.png'), fullPage: true });
});

test("a zip of several meshes: one figure set per member, the command line's JSON", async () => {
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-web-'));
  const members = ['stl-models/unitCube.ascii.stl', 'geomview/dodec.off', 'libcgal-demo/sphere.ply'];
  const file = path.join(dir, 'parts.zip');
  writeFileSync(file, zipSync(Object.fromEntries(members.map((m) => [path.basename(m), readFileSync(corpus(m))]))));
  await choose(file);
  const shown = await card('parts.zip');
  const native = runCli(['measure', '--json', ...flags, 'parts.zip'], dir);
  assert.equal(shown.json, native.stdout);
  assert.equal(JSON.parse(shown.json).length, 3);
  for (const m of members) assert.ok(shown.text.includes(`parts.zip:${path.basename(m)}`));
  await page.screenshot({ path: path.join(screens, 'parts.zip.png'), fullPage: true });
});

test('two files: their overlap on request, the command line\'s JSON (less its time)', async () => {
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-web-'));
  const cube = (o) => {
    const v = [];
    for (const z of [0, 2]) for (const y of [0, 2]) for (const x of [0, 2]) v.push(`v ${x + o} ${y + o} ${z + o}`);
    const f = [[1, 3, 4, 2], [5, 6, 8, 7], [1, 2, 6, 5], [3, 7, 8, 4], [1, 5, 7, 3], [2, 4, 8, 6]];
    return [...v, ...f.map((q) => 'f ' + q.join(' '))].join('\n') + '\n';
  };
  writeFileSync(path.join(dir, 'cube-a.obj'), cube(0));
  writeFileSync(path.join(dir, 'cube-b.obj'), cube(1));
  await choose(path.join(dir, 'cube-a.obj'), path.join(dir, 'cube-b.obj'));
  const before = await page.evaluate(() => Number(document.body.dataset.done ?? 0));
  await page.evaluate(() => {
    const pick = (id, name) => {
      const s = document.getElementById(id);
      s.value = [...s.options].reverse().find((o) => o.textContent === name).value;
    };
    pick('overlap-a', 'cube-a.obj');
    pick('overlap-b', 'cube-b.obj');
  });
  await page.click('#overlap-go');
  await page.waitForFunction((n) => Number(document.body.dataset.done ?? 0) > n, { timeout: 120000 }, before);
  const shown = await page.$eval('article[data-overlap="cube-a.obj cube-b.obj"]', (a) => ({ json: a.dataset.json, text: a.innerText }));
  const native = runCli(['overlap', '--json', '--units', 'mm', '--to', 'mm', 'cube-a.obj', 'cube-b.obj'], dir);
  const untimed = (t) => t.replace(/\n\s*"seconds": [^\n]*\n/, '\n').replace(/,\n}/, '\n}');
  assert.equal(untimed(shown.json), untimed(native.stdout));
  const r = JSON.parse(shown.json);
  assert.deepEqual([r.intersection, r.union, r.a_minus_b], [1, 15, 7]);
  assert.match(shown.text, /A ∩ B\s+1\b/);
  await page.screenshot({ path: path.join(screens, 'overlap.png'), fullPage: true });
});

test('a broken file: a clear message, and the page still works', async () => {
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-web-'));
  const file = path.join(dir, 'broken.stl');
  writeFileSync(file, 'solid broken\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 nonsense\n');
  await choose(file);
  const shown = await card('broken.stl');
  const native = runCli(['measure', '--json', ...flags, 'broken.stl'], dir);
  assert.equal(shown.exitCode, native.code);
  assert.equal(shown.json, native.stdout);
  for (const m of native.messages) assert.ok(shown.text.includes(m.replace(/^polyvol: /, '')), `the page says: ${m}`);
  await page.screenshot({ path: path.join(screens, 'broken.png'), fullPage: true });
  const cube = corpus('stl-models/unitCube.ascii.stl');
  await choose(cube);
  assert.equal((await card('unitCube.ascii.stl')).exitCode, 0);
});

test('the worker reads a File as the core asks (WORKERFS) and reports progress: volume --stream --json, 8,334 unit cubes', async () => {
  // 8,334 disjoint unit cubes at x = 2k, 12 triangles each: 100,008 triangles, volume 8334.
  const QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
  const cubes = 8334, n = 12 * cubes;
  const stl = new Uint8Array(84 + 50 * n);
  const view = new DataView(stl.buffer);
  view.setUint32(80, n, true);
  let t = 0;
  for (let k = 0; k < cubes; ++k) {
    const p = [...Array(8).keys()].map((i) => [2 * k + (i & 1), (i >> 1) & 1, (i >> 2) & 1]);
    for (const [a, b, c, d] of QUADS)
      for (const tri of [[a, b, c], [a, c, d]]) tri.flatMap((i) => p[i]).forEach((x, j) => view.setFloat32(84 + 50 * t + 12 + 4 * j, x, true)), ++t;
  }
  const dir = mkdtempSync(path.join(tmpdir(), 'polyvol-stream-'));
  writeFileSync(path.join(dir, 'cubes.stl'), stl);
  const native = runCli(['volume', '--stream', '--json', 'cubes.stl'], dir);
  assert.equal(native.code, 0);
  const input = await page.evaluateHandle(() => {
    const e = Object.assign(document.createElement('input'), { type: 'file', hidden: true });
    document.body.append(e);
    return e;
  });
  await input.uploadFile(path.join(dir, 'cubes.stl'));
  const { answer, progress } = await page.evaluate((e) => new Promise((resolve, reject) => {
    const worker = new Worker('/worker.js', { type: 'module' });
    const progress = [];
    worker.onmessage = ({ data: m }) => {
      if (m.progress) return progress.push(m.progress);
      worker.terminate();
      if (m.error !== undefined) reject(new Error(m.error));
      else resolve({ answer: m.answer, progress });
    };
    worker.postMessage({ id: 1, command: 'volume', files: [{ name: 'cubes.stl', data: e.files[0] }], options: { stream: true } });
  }), input);
  assert.equal(answer.stdout, native.stdout);
  assert.equal(JSON.parse(answer.stdout)[0].volume, 8334);
  assert.deepEqual(progress[0], { file: 'cubes.stl', stage: 'reading', fraction: 0 });
  assert.deepEqual(progress.at(-1), { file: 'cubes.stl', stage: 'measuring', fraction: 1 });
  assert.ok(progress.filter((p) => p.stage === 'reading' && p.fraction > 0 && p.fraction < 1).length >= 20, JSON.stringify(progress));
});

test('the page asked nothing of any other origin and threw nothing', () => {
  assert.deepEqual(foreign, []);
  assert.deepEqual(pageErrors, []);
});
