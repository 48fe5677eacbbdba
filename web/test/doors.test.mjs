// One answer from every door of the package: the cases of
// tests/python/test_every_door.py (the same cubes, the same refusals)
// through `volume` (loaded, streamed, streamed volume only), `measure`,
// `check` and `overlap` with a box around them (A ∩ box and box ∩ A are the
// solid). Each gives the solid's volume, or refuses with exit code 3 and
// the library's words; `check` judges the file as it is.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';

import { loadPackage, root } from './environment.mjs';

const { createPolyvol } = await loadPackage();
const polyvol = await createPolyvol();

// A cube [x, x+s]^3 as 8 vertices and 6 outward quads (OBJ numbering from 0).
const QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
const cube = ([x, y, z], s) => [...Array(8).keys()].map((i) => [x + s * (i & 1), y + s * ((i >> 1) & 1), z + s * ((i >> 2) & 1)]);

// Cubes [lo, side] in one OBJ; flip: 'c,q' reversed ('all,c': every quad of
// cube c); drop: 'c,q' left out; move [c, vertex, dx]: the first quad at that
// vertex uses a copy of it moved by dx along x (a gap).
function obj(cubes, { flip = [], drop = [], move = null } = {}) {
  const lines = [];
  let base = 0;
  cubes.forEach(([lo, side], c) => {
    const points = cube(lo, side);
    if (move && move[0] === c) points.push([points[move[1]][0] + move[2], points[move[1]][1], points[move[1]][2]]);
    lines.push(...points.map((p) => `v ${p.join(' ')}`));
    let moved = false;
    QUADS.forEach((quad, q) => {
      if (drop.includes(`${c},${q}`)) return;
      let f = flip.includes(`${c},${q}`) || flip.includes(`all,${c}`) ? [...quad].reverse() : quad;
      if (move && move[0] === c && f.includes(move[1]) && !moved) {
        f = f.map((i) => (i === move[1] ? 8 : i));
        moved = true;
      }
      lines.push(`f ${f.map((i) => base + i + 1).join(' ')}`);
    });
    base += points.length;
  });
  return `${lines.join('\n')}\n`;
}

const ONE = [[[0, 0, 0], 2]];
const TWO = [[[0, 0, 0], 2], [[1, 1, 1], 2]];  // overlapping in a unit cube: the solid is 15
const SELF = readFileSync(path.join(root, 'tests', 'data', 'self_crossing', 'one.obj'));
const SELF_VOLUME = 4.932123991149121;
const BOX = obj([[[-10, -10, -10], 30]]);

// name: [file, the solid's volume or the refusal's words, a solid as it is, doors that refuse it (documented)]
const CASES = {
  'clean cube': [obj(ONE), 8, true, []],
  'two cubes': [obj(TWO), 15, true, []],
  'inside-out cube': [obj(ONE, { flip: ['all,0'] }), 8, false, []],
  // A streamed binary STL is not checked for crossings: an OBJ is loaded by every door.
  'self-crossing shell': [SELF, SELF_VOLUME, true, []],
  'flipped face': [obj(ONE, { flip: ['0,1'] }), 'misoriented', false, []],
  'open cube': [obj(ONE, { drop: ['0,1'] }), 'not a closed surface', false, []],
  '1e-7 gap': [obj(ONE, { move: [0, 7, 1e-7] }), 'not a closed surface', false, []],
};

const volumeOf = (r, key) => (r.exitCode === 3 ? ['refused', r.messages.join('\n')] : [key(r), r.messages.join('\n')]);
const DOORS = {
  volume: (f) => volumeOf(polyvol.volume(f, 'case.obj'), (r) => r.results[0].volume),
  'volume stream': (f) => volumeOf(polyvol.volume(f, 'case.obj', { stream: true }), (r) => r.results[0].volume),
  'volume stream volumeOnly': (f) => volumeOf(polyvol.volume(f, 'case.obj', { stream: true, volumeOnly: true }), (r) => r.results[0].volume),
  measure: (f) => volumeOf(polyvol.measure(f, 'case.obj'), (r) => r.results[0].volume),
  'measure (page: units, a density)': (f) => volumeOf(
    polyvol.measure(f, 'case.obj', { units: 'mm', to: 'mm', unitsWhereUnstated: true, density: '1.24g/cm3', massUnit: 'g' }),
    (r) => r.results[0].volume),
  'overlap A': (f) => volumeOf(polyvol.overlap(f, 'case.obj', BOX, 'box.obj'), (r) => r.result.intersection),
  'overlap B': (f) => volumeOf(polyvol.overlap(BOX, 'box.obj', f, 'case.obj'), (r) => r.result.intersection),
};

for (const [name, [file, want, ready, notYet]] of Object.entries(CASES)) {
  test(`${name}: every door gives the same solid or the same refusal`, () => {
    for (const [door, run] of Object.entries(DOORS)) {
      const [got, said] = run(file);
      if (notYet.includes(door) || typeof want === 'string') {
        assert.equal(got, 'refused', `${door}: ${got}`);
        if (typeof want === 'string') assert.ok(said.includes(want), `${door}: ${said}`);
      } else {
        assert.equal(got, want, `${door}: ${said}`);
      }
    }
  });
  test(`${name}: check judges the file as it is`, () => {
    const r = polyvol.check(file, 'case.obj');
    assert.equal(r.exitCode, ready ? 0 : 3, r.messages.join('\n'));
    assert.equal(r.results[0].ready, ready);
    assert.equal(r.results[0].repairs.length === 0, ready);
  });
}
