// The npm package's `volume` (WebAssembly, Node) against the native command
// line on one core, in paired rounds, the file read on both sides:
//   node web/bench/volume.mjs FILE.stl [ROUNDS]
// Prints each round and the medians. Native, `taskset -c 0 polyvol`:
// `volume FILE` (the table: a large binary STL streamed, one pass, the
// centroid bounded), `volume --volume-only` (one pass, the volume alone) and
// `volume --json` (loaded and checked in full). The package (readFileSync +
// the call; the module instantiated once, before the rounds, as a page has
// it): loaded as --json; streamed (`stream`: `volume --stream --json`, the
// centroid correctly rounded: more passes where its sums cancel); streamed
// volume only (`stream`, `volumeOnly`: the table's one pass, less area and
// centroid). `read` is readFileSync alone.
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';

import { cli, loadPackage } from '../test/environment.mjs';

const file = process.argv[2];
const rounds = Number(process.argv[3] ?? 5);
if (!file) throw new Error('usage: node web/bench/volume.mjs FILE.stl [ROUNDS]');
const { createPolyvol } = await loadPackage();
const polyvol = await createPolyvol();
const name = path.basename(file);

const seconds = (f) => {
  const t = process.hrtime.bigint();
  f();
  return Number(process.hrtime.bigint() - t) / 1e9;
};
const native = (args) => () => {
  const r = spawnSync('taskset', ['-c', '0', cli, ...args, file], { encoding: 'utf8', maxBuffer: 1 << 28 });
  if (r.status !== 0) throw new Error(r.stderr);
};
const wasm = (options) => () => {
  const r = polyvol.volume(readFileSync(file), name, options);
  if (r.exitCode !== 0) throw new Error(r.messages.join('\n'));
};
const routes = {
  'native table': native(['volume']),
  'native --volume-only': native(['volume', '--volume-only']),
  'native --json': native(['volume', '--json']),
  'read': () => readFileSync(file),
  'wasm': wasm({}),
  'wasm stream': wasm({ stream: true }),
  'wasm stream volumeOnly': wasm({ stream: true, volumeOnly: true }),
};
const times = Object.fromEntries(Object.keys(routes).map((k) => [k, []]));
for (let i = 0; i < rounds; ++i) {
  for (const [k, f] of Object.entries(routes)) times[k].push(seconds(f));
  console.log(`round ${i + 1}: ${Object.entries(times).map(([k, v]) => `${k} ${v[i].toFixed(3)} s`).join(', ')}`);
}
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
const m = Object.fromEntries(Object.entries(times).map(([k, v]) => [k, median(v)]));
console.log(`medians: ${Object.entries(m).map(([k, v]) => `${k} ${v.toFixed(3)} s`).join(', ')}`);
console.log(`wasm / --json ${(m.wasm / m['native --json']).toFixed(2)}, wasm stream / table ${(m['wasm stream'] / m['native table']).toFixed(2)}, ` +
  `wasm stream volumeOnly / table ${(m['wasm stream volumeOnly'] / m['native table']).toFixed(2)}, ` +
  `/ native --volume-only ${(m['wasm stream volumeOnly'] / m['native --volume-only']).toFixed(2)}`);
