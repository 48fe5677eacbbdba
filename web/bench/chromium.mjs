// The package's `volume` in Debian's chromium (headless), against the native
// command line on one core, in paired rounds, the file read on both sides:
//   node web/bench/chromium.mjs FILE.stl [ROUNDS]
// The page's directory (build-wasm/page) is served locally with FILE as
// /bench-file. Two ways in, each round:
//  * as a person gives it: FILE chosen on a file input, handed as a File to
//    the page's own worker (page/worker.js, the module instantiated before
//    the rounds), which reads it window by window; `file` is the call
//    volume({stream, volumeOnly}) from posting to the answer, `file bytes`
//    the same after file.arrayBuffer() (the whole file read first, the
//    bytes handed over), `file read` file.arrayBuffer() alone;
//  * fetched from the server on the page's thread: `fetch` is the fetch and
//    arrayBuffer() alone, then volume loaded (as --json), streamed (as
//    --stream --json) and streamed volume only (--stream --volume-only
//    --json, the table's one pass).
// Prints each round and the medians.
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { createServer } from 'node:http';
import path from 'node:path';

import puppeteer from 'puppeteer-core';

import { cli, packageDir } from '../test/environment.mjs';

const file = process.argv[2];
const rounds = Number(process.argv[3] ?? 5);
if (!file) throw new Error('usage: node web/bench/chromium.mjs FILE.stl [ROUNDS]');
const pageDir = path.join(path.dirname(packageDir), 'page');
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm' };
const server = createServer((req, res) => {
  const url = new URL(req.url, 'http://x').pathname;
  try {
    const p = url === '/bench-file' ? file : path.join(pageDir, decodeURIComponent(url));
    const body = readFileSync(p);
    res.writeHead(200, { 'content-type': types[path.extname(p)] ?? 'application/octet-stream' });
    res.end(body);
  } catch {
    res.writeHead(404).end();
  }
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const origin = `http://127.0.0.1:${server.address().port}`;
const browser = await puppeteer.launch({
  executablePath: process.env.POLYVOL_CHROMIUM ?? '/usr/bin/chromium', args: ['--headless=new', '--no-sandbox', '--disable-gpu'],
});
try {
  const page = await browser.newPage();
  await page.goto(`${origin}/index.html`, { waitUntil: 'load' });
  await page.evaluate(async () => {
    const { createPolyvol } = await import('/polyvol/browser.mjs');
    const fflate = await import('/vendor/fflate.mjs');
    const { parseXml } = await import('/vendor/parse-xml.mjs');
    window.benchPolyvol = await createPolyvol({ fflate, parseXml });
  });
  // The file input and the worker.
  const input = await page.evaluateHandle(() => {
    const e = Object.assign(document.createElement('input'), { type: 'file', id: 'bench-input' });
    document.body.append(e);
    window.benchWorker = new Worker('/worker.js', { type: 'module' });
    return e;
  });
  await input.uploadFile(file);
  const viaWorker = (bytes) => page.evaluate(async (whole) => {
    const f = document.getElementById('bench-input').files[0];
    const t = performance.now();
    const data = whole ? await f.arrayBuffer() : f;
    const answer = await new Promise((resolve, reject) => {
      window.benchWorker.onmessage = ({ data: m }) => {
        if (m.error !== undefined) reject(new Error(m.error));
        else if (!m.progress) resolve(m.answer);
      };
      window.benchWorker.postMessage({ id: 1, command: 'volume', files: [{ name: f.name, data }],
        options: { stream: true, volumeOnly: true } }, whole ? [data] : []);
    });
    if (answer.exitCode !== 0) throw new Error(answer.messages.join('\n'));
    return (performance.now() - t) / 1000;
  }, bytes);
  await viaWorker(false);  // the worker's module instantiated, its code warm
  const fileRead = () => page.evaluate(async () => {
    const t = performance.now();
    await document.getElementById('bench-input').files[0].arrayBuffer();
    return (performance.now() - t) / 1000;
  });
  const inPage = (options) => page.evaluate(async (o) => {
    const t = performance.now();
    const data = await (await fetch('/bench-file')).arrayBuffer();
    if (o === null) return (performance.now() - t) / 1000;  // the fetch alone
    const r = window.benchPolyvol.volume(data, 'bench.stl', o);
    if (r.exitCode !== 0) throw new Error(r.messages.join('\n'));
    return (performance.now() - t) / 1000;
  }, options);
  const native = () => {
    const t = process.hrtime.bigint();
    const r = spawnSync('taskset', ['-c', '0', cli, 'volume', file], { encoding: 'utf8', maxBuffer: 1 << 28 });
    if (r.status !== 0) throw new Error(r.stderr);
    return Number(process.hrtime.bigint() - t) / 1e9;
  };
  const routes = {
    'native table': async () => native(),
    file: () => viaWorker(false),
    'file bytes': () => viaWorker(true),
    'file read': fileRead,
    fetch: () => inPage(null),
    volume: () => inPage({}),
    stream: () => inPage({ stream: true }),
    'stream volumeOnly': () => inPage({ stream: true, volumeOnly: true }),
  };
  const times = Object.fromEntries(Object.keys(routes).map((k) => [k, []]));
  for (let i = 0; i < rounds; ++i) {
    for (const [k, f] of Object.entries(routes)) times[k].push(await f());
    console.log(`round ${i + 1}: ${Object.entries(times).map(([k, v]) => `${k} ${v[i].toFixed(3)} s`).join(', ')}`);
  }
  const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
  const m = Object.fromEntries(Object.entries(times).map(([k, v]) => [k, median(v)]));
  console.log(`medians (chromium): ${Object.entries(m).map(([k, v]) => `${k} ${v.toFixed(3)} s`).join(', ')}; ` +
    `file / table ${(m.file / m['native table']).toFixed(2)}, file bytes / table ` +
    `${(m['file bytes'] / m['native table']).toFixed(2)}, stream volumeOnly (fetched) / table ` +
    `${(m['stream volumeOnly'] / m['native table']).toFixed(2)}`);
} finally {
  await browser.close();
  server.close();
}
