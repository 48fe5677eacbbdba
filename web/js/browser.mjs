// polyvol for browsers and workers: the module loaded beside this file.
import createPolyvolModule from './polyvol.web.mjs';
import { bind, sharedCalls } from './core.mjs';

// fflate (npm) unpacks gzip and zip for the module: imported by name (a
// bundler resolves it), or given, e.g. by a page without a bundler.
export async function createPolyvol({ wasmUrl = new URL('./polyvol.wasm', import.meta.url), fflate } = {}) {
  fflate ??= await import('fflate');
  const module = await createPolyvolModule({ locateFile: () => String(wasmUrl), fflate, print: () => {}, printErr: () => {} });
  return bind(module);
}

export const { volume, measure, check, overlap, run } = sharedCalls(createPolyvol);
