// polyvol for Node (>= 20): the module loaded from this directory.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';

import * as fflate from 'fflate';

import { bind, sharedCalls } from './core.mjs';

const require = createRequire(import.meta.url);

export async function createPolyvol() {
  const factory = require('./polyvol.cjs');
  // The bytes handed over: Emscripten 3.1.6 would fetch() a path under Node 20.
  const wasmBinary = await readFile(new URL('./polyvol.wasm', import.meta.url));
  // fflate unpacks gzip and zip for the module (web/src/io_in_javascript.cpp).
  return bind(await factory({ wasmBinary, fflate, print: () => {}, printErr: () => {} }));
}

export const { volume, measure, check, overlap, run } = sharedCalls(createPolyvol);
