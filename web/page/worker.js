// The page's worker: the WebAssembly core runs here, so that a large file
// never freezes the page, and reads a File as the core asks (FileReaderSync:
// whole, once, into the module; a streamed STL window by window). Messages:
// {id, command, files: [{name, data: a File, Blob or ArrayBuffer}], options}
// in (command 'mesh': the package's mesh() of the first file);
// {id, progress: {file, stage, fraction}} while a file is measured, then
// {id, answer} or {id, error} out.
import { createPolyvol } from './polyvol/browser.mjs';
import * as fflate from './vendor/fflate.mjs';
import { parseXml } from './vendor/parse-xml.mjs';

const ready = createPolyvol({ fflate, parseXml });

self.onmessage = async ({ data: { id, command, files, options } }) => {
  try {
    const polyvol = await ready;
    if (command === 'mesh') {
      // The 3D view's arrays (one buffer), handed over rather than copied.
      const m = polyvol.mesh(files[0].data, files[0].name, options);
      self.postMessage({ id, answer: m }, [m.positions.buffer]);
    } else {
      const onProgress = (progress) => self.postMessage({ id, progress });
      self.postMessage({ id, answer: polyvol.run(command, files, { ...options, onProgress }) });
    }
  } catch (e) {
    self.postMessage({ id, error: String(e && e.message ? e.message : e) });
  }
};
