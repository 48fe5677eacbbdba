// The npm package's `volume` (WebAssembly, Node) against the native command
// line on one core, in paired rounds, the file read on both sides:
//   node web/bench/volume.mjs FILE.stl [ROUNDS]
// Prints each round and the medians: native `taskset -c 0 polyvol volume FILE`
// (the table: a large binary STL streamed) and `volume --json FILE` (loaded
// and checked in full, what the package computes), and the package's call
// (readFile + volume; the module instantiated once, before the rounds, as a
// page has it), loaded as --json and streamed (the option stream: volume
// --stream --json's bytes, the route of the native table).
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';

import { cli, loadPackage } from '../test/environment.mjs';

const file = process.argv[2];
const rounds = Number(process.argv[3] ?? 5);
if (!file) throw new Error('usage: node web/bench/volume.mjs FILE.stl [ROUNDS]');
const { createPolyvol } = await loadPackage();
const polyvol = await createPolyvol();

const seconds = (f) => {
  const t = process.hrtime.bigint();
  f();
  return Number(process.hrtime.bigint() - t) / 1e9;
};
const native = (args) => () => {
  const r = spawnSync('taskset', ['-c', '0', cli, ...args, file], { encoding: 'utf8', maxBuffer: 1 << 28 });
  if (r.status !== 0) throw new Error(r.stderr);
};
const times = { table: [], json: [], wasm: [], stream: [] };
for (let i = 0; i < rounds; ++i) {
  times.table.push(seconds(native(['volume'])));
  times.json.push(seconds(native(['volume', '--json'])));
  times.wasm.push(seconds(() => {
    const r = polyvol.volume(readFileSync(file), path.basename(file));
    if (r.exitCode !== 0) throw new Error(r.messages.join('\n'));
  }));
  times.stream.push(seconds(() => {
    const r = polyvol.volume(readFileSync(file), path.basename(file), { stream: true });
    if (r.exitCode !== 0) throw new Error(r.messages.join('\n'));
  }));
  console.log(`round ${i + 1}: native table ${times.table[i].toFixed(3)} s, native --json ${times.json[i].toFixed(3)} s, ` +
    `wasm ${times.wasm[i].toFixed(3)} s, wasm stream ${times.stream[i].toFixed(3)} s`);
}
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
const m = Object.fromEntries(Object.entries(times).map(([k, v]) => [k, median(v)]));
console.log(`medians: native table ${m.table.toFixed(3)} s, native --json ${m.json.toFixed(3)} s, wasm ${m.wasm.toFixed(3)} s, ` +
  `wasm stream ${m.stream.toFixed(3)} s; wasm / --json ${(m.wasm / m.json).toFixed(2)}, wasm stream / table ${(m.stream / m.table).toFixed(2)}`);
