// polyvol for browsers and workers: the module loaded beside this file.
import createPolyvolModule from './polyvol.web.mjs';
import { bind } from './core.mjs';

// fflate (npm) unpacks gzip and zip for the module: imported by name (a
// bundler resolves it), or given, e.g. by a page without a bundler.
export async function createPolyvol({ wasmUrl = new URL('./polyvol.wasm', import.meta.url), fflate } = {}) {
  fflate ??= await import('fflate');
  const module = await createPolyvolModule({ locateFile: () => String(wasmUrl), fflate, print: () => {}, printErr: () => {} });
  return bind(module);
}

let shared;
const instance = () => (shared ??= createPolyvol());

export const volume = async (...a) => (await instance()).volume(...a);
export const measure = async (...a) => (await instance()).measure(...a);
export const check = async (...a) => (await instance()).check(...a);
export const overlap = async (...a) => (await instance()).overlap(...a);
export const run = async (...a) => (await instance()).run(...a);
