// polyvol for browsers and workers: the module loaded beside this file.
import createPolyvolModule from './polyvol.web.mjs';
import { bind, sharedCalls } from './core.mjs';
import { xmlTables } from './xml.mjs';

// fflate (npm) unpacks gzip and zip for the module, @rgrove/parse-xml (npm)
// reads 3MF's and AMF's XML: imported by name (a bundler resolves them), or
// given, e.g. by a page without a bundler.
export async function createPolyvol({ wasmUrl = new URL('./polyvol.wasm', import.meta.url), fflate, parseXml } = {}) {
  fflate ??= await import('fflate');
  parseXml ??= (await import('@rgrove/parse-xml')).parseXml;
  const module = await createPolyvolModule({
    locateFile: () => String(wasmUrl), fflate, xmlTables: (bytes) => xmlTables(parseXml, bytes),
    print: () => {}, printErr: () => {},
  });
  return bind(module);
}

export const { volume, measure, check, overlap, mesh, run } = sharedCalls(createPolyvol);
