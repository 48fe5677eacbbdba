// The package's `volume` in Debian's chromium (headless), against the native
// command line on one core, in paired rounds, the file read on both sides:
//   node web/bench/chromium.mjs FILE.stl [ROUNDS]
// The page's directory (build-wasm/page) is served locally with FILE as
// /bench-file; in the page the module is instantiated once, then each round
// fetches the file and calls volume on it (loaded, as --json; and streamed, as
// --stream --json). Prints each round and the medians.
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
  const inPage = (options) => page.evaluate(async (o) => {
    const t = performance.now();
    const data = await (await fetch('/bench-file')).arrayBuffer();
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
  const times = { table: [], loaded: [], stream: [] };
  for (let i = 0; i < rounds; ++i) {
    times.table.push(native());
    times.loaded.push(await inPage({}));
    times.stream.push(await inPage({ stream: true }));
    console.log(`round ${i + 1}: native table ${times.table[i].toFixed(3)} s, chromium volume ${times.loaded[i].toFixed(3)} s, ` +
      `chromium volume stream ${times.stream[i].toFixed(3)} s`);
  }
  const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
  const m = Object.fromEntries(Object.entries(times).map(([k, v]) => [k, median(v)]));
  console.log(`medians: native table ${m.table.toFixed(3)} s, chromium volume ${m.loaded.toFixed(3)} s, chromium stream ` +
    `${m.stream.toFixed(3)} s; stream / table ${(m.stream / m.table).toFixed(2)}`);
} finally {
  await browser.close();
  server.close();
}
