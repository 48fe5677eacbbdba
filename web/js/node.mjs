// polyvol for Node (>= 20): the module loaded from this directory.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';

import { parseXml } from '@rgrove/parse-xml';
import * as fflate from 'fflate';

import { bind, sharedCalls } from './core.mjs';
import { xmlTables } from './xml.mjs';

const require = createRequire(import.meta.url);

export async function createPolyvol() {
  const factory = require('./polyvol.cjs');
  // The bytes handed over: Emscripten 3.1.6 would fetch() a path under Node 20.
  const wasmBinary = await readFile(new URL('./polyvol.wasm', import.meta.url));
  // fflate unpacks gzip and zip for the module (web/src/io_in_javascript.cpp);
  // parse-xml reads 3MF's and AMF's XML (web/src/xml_in_javascript.cpp).
  const module = await factory({ wasmBinary, fflate, xmlTables: (bytes) => xmlTables(parseXml, bytes), print: () => {}, printErr: () => {} });
  return bind(module);
}

export const { volume, measure, check, overlap, mesh, run } = sharedCalls(createPolyvol);
