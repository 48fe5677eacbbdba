// polyvol for Node (>= 20): the module loaded from this directory.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';

import * as fflate from 'fflate';

import { bind } from './core.mjs';

const require = createRequire(import.meta.url);

export async function createPolyvol() {
  const factory = require('./polyvol.cjs');
  // The bytes handed over: Emscripten 3.1.6 would fetch() a path under Node 20.
  const wasmBinary = await readFile(new URL('./polyvol.wasm', import.meta.url));
  // fflate unpacks gzip and zip for the module (web/src/io_in_javascript.cpp).
  return bind(await factory({ wasmBinary, fflate, print: () => {}, printErr: () => {} }));
}

let shared;
const instance = () => (shared ??= createPolyvol());

export const volume = async (...a) => (await instance()).volume(...a);
export const measure = async (...a) => (await instance()).measure(...a);
export const check = async (...a) => (await instance()).check(...a);
export const overlap = async (...a) => (await instance()).overlap(...a);
export const run = async (...a) => (await instance()).run(...a);
