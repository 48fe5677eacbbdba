// The package's calls over an instantiated module (web/src/polyvol_wasm.cpp):
// files go into the module's file system, one directory per call, named as
// given (so the results name them as `polyvol` run in their directory
// does); the answer is the command line's JSON, parsed. Bytes are copied
// into the module's memory file system (MEMFS); a Blob or File in a worker
// is mounted (WORKERFS) and read as the core reads it: a streamed binary
// STL window by window, any other file whole, once, into the module.

const COMMANDS = new Set(['volume', 'measure', 'check', 'overlap']);

// The module's options: camelCase or the command line's snake_case words.
function words(options = {}) {
  const out = {};
  const key = (k) => k.replace(/[A-Z]/g, (c) => '_' + c.toLowerCase());
  for (const [k, v] of Object.entries(options)) if (v !== undefined && v !== null) out[key(k)] = v;
  return out;
}

const isBlob = (data) => typeof Blob !== 'undefined' && data instanceof Blob;

function bytesOf(data) {
  if (data instanceof Uint8Array) return data;
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  if (ArrayBuffer.isView(data)) return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  if (typeof data === 'string') return new TextEncoder().encode(data);
  throw new TypeError('a file is an ArrayBuffer, a typed array or a string');
}

// The last part of a name, so that a file always lands in the call's directory.
function baseName(name) {
  const base = String(name).split(/[\\/]/).pop();
  if (!base || base === '.' || base === '..') throw new TypeError(`not a file name: '${name}'`);
  return base;
}

export function bind(Module) {
  const { FS } = Module;
  let calls = 0;

  // Calls fn(names) with the files written into a directory of their own,
  // the current one meanwhile; names are those of the files not marked companion.
  function inDirectory(files, fn) {
    // Blobs are read where FileReaderSync is (a worker): then every file of
    // the call is mounted as one (bytes as a Blob of their own).
    const mounted = files.some((f) => isBlob(f.data));
    if (mounted && typeof FileReaderSync === 'undefined')
      throw new TypeError('a Blob or File is read in a worker (FileReaderSync); elsewhere pass its arrayBuffer()');
    const dir = `/call${++calls}`;
    FS.mkdir(dir);
    const names = [];
    const blobs = [];
    let mountedAt = null;
    try {
      for (const f of files) {
        let name = baseName(f.name);
        // A second file of the same name (overlap of two versions of a part) in a directory of its own.
        const taken = (n) => (mounted ? blobs.some((b) => b.name === n || b.name.startsWith(`${n}/`)) : FS.analyzePath(`${dir}/${n}`).exists);
        if (taken(name)) {
          let k = 2;
          while (taken(`copy${k}`)) ++k;
          if (!mounted) FS.mkdir(`${dir}/copy${k}`);
          name = `copy${k}/${name}`;
        }
        if (mounted) blobs.push({ name, data: isBlob(f.data) ? f.data : new Blob([bytesOf(f.data)]) });
        else FS.writeFile(`${dir}/${name}`, bytesOf(f.data));
        if (!f.companion) names.push(name);
      }
      if (mounted) {
        FS.mount(FS.filesystems.WORKERFS, { blobs }, dir);
        mountedAt = dir;
      }
      FS.chdir(dir);
      return fn(names);
    } finally {
      FS.chdir('/');
      const remove = (d) => {
        for (const name of FS.readdir(d)) {
          if (name === '.' || name === '..') continue;
          const p = `${d}/${name}`;
          if (FS.isDir(FS.stat(p).mode)) remove(p);
          else FS.unlink(p);
        }
        FS.rmdir(d);
      };
      if (mountedAt) FS.unmount(mountedAt);
      if (mounted) FS.rmdir(dir);
      else remove(dir);
    }
  }

  // Calls the module's entry `fn` with the request's text; the answer pointer
  // is handed to `read` and freed.
  function call(fn, request, read, ...extra) {
    const size = Module.lengthBytesUTF8(request) + 1;
    const ptr = Module._malloc(size) >>> 0;
    if (!ptr) throw new RangeError('polyvol: out of memory for the request');
    try {
      Module.stringToUTF8(request, ptr, size);
      const out = fn(ptr, ...extra) >>> 0;  // a pointer past 2 GiB arrives negative
      if (!out) throw new RangeError('polyvol: out of memory for the answer');
      try {
        return read(out);
      } finally {
        Module._polyvol_free(out);
      }
    } finally {
      Module._free(ptr);
    }
  }

  // One request: {exitCode, stdout (the command line's --json text), messages, csv (measure)}.
  // options.onProgress({file, stage, fraction}), if given, is called while
  // a file is measured: stage 'reading', 'checking' or 'measuring', each
  // as it begins (fraction 0); a streamed STL's passes by whole percents.
  function run(command, files, options = {}) {
    if (!COMMANDS.has(command)) throw new TypeError(`unknown command '${command}' (volume, measure, check or overlap)`);
    const { onProgress, ...rest } = options;
    return inDirectory(files, (names) => {
      const request = JSON.stringify({ command, files: names, options: words(rest) });
      Module.onProgress = onProgress && ((file, stage, fraction) => onProgress({ file, stage, fraction }));
      try {
        const answer = call(Module._polyvol_run, request, (out) => JSON.parse(Module.UTF8ToString(out)));
        return { exitCode: answer.exit_code, stdout: answer.stdout, messages: answer.messages, csv: answer.csv, noteWords: answer.note_words };
      } finally {
        Module.onProgress = undefined;
      }
    });
  }

  // A file's triangles and its problem edges, for a 3D view (web/src/polyvol_wasm.cpp, mesh_block).
  function mesh(data, name, { member = '', edgeLimit = 200000, companions = [] } = {}) {
    return inDirectory([{ data, name }, ...companions.map((c) => ({ ...c, companion: true }))], ([file]) => {
      const request = JSON.stringify({ file, member, edge_limit: edgeLimit });
      const sizePtr = Module._malloc(4) >>> 0;
      if (!sizePtr) throw new RangeError('polyvol: out of memory for the request');
      try {
        return call(Module._polyvol_mesh, request, (out) => {
          const block = Module.HEAPU8.slice(out, out + Module.HEAPU32[sizePtr >>> 2]).buffer;
          const n = new DataView(block).getUint32(0, true);
          const h = JSON.parse(new TextDecoder().decode(new Uint8Array(block, 4, n)));
          const a = h.arrays;
          return {
            exitCode: h.exit_code,
            error: h.error,
            shells: h.shells,
            edges: { boundary: h.boundary_edges, nonmanifold: h.nonmanifold_edges, misoriented: h.misoriented_edges, unbalanced: h.unbalanced_edges },
            positions: new Float32Array(block, a.positions, 3 * h.vertices),
            triangles: new Uint32Array(block, a.triangles, 3 * h.triangles),
            triangleShell: new Uint32Array(block, a.triangle_shell, h.triangles),
            problemEdges: new Float32Array(block, a.problem_edges, 6 * h.problem_edges),
            problems: new Uint8Array(block, a.problems, h.problem_edges),
          };
        }, sizePtr);
      } finally {
        Module._free(sizePtr);
      }
    });
  }

  // The command line's JSON for one file (with its companions, e.g. a .gltf's
  // .bin): an array with one object per mesh, keys as `polyvol CMD --json`.
  const one = (command) => (data, name, options = {}, companions = []) => {
    const r = run(command, [{ data, name }, ...companions.map((c) => ({ ...c, companion: true }))], options);
    return { results: r.stdout ? JSON.parse(r.stdout) : [], exitCode: r.exitCode, messages: r.messages, json: r.stdout, csv: r.csv, noteWords: r.noteWords };
  };
  // `polyvol overlap --json A B`: A ∩ B, A ∪ B, A − B and B − A, one object.
  const overlap = (dataA, nameA, dataB, nameB, options = {}) => {
    const r = run('overlap', [{ data: dataA, name: nameA }, { data: dataB, name: nameB }], options);
    return { result: r.stdout ? JSON.parse(r.stdout) : null, exitCode: r.exitCode, messages: r.messages, json: r.stdout };
  };
  return { run, mesh, volume: one('volume'), measure: one('measure'), check: one('check'), overlap };
}

// The calls on one module made on first use (the package's top-level
// functions), given how this platform makes a module.
export function sharedCalls(createPolyvol) {
  let shared;
  const instance = () => (shared ??= createPolyvol());
  const call = (name) => async (...a) => (await instance())[name](...a);
  return { volume: call('volume'), measure: call('measure'), check: call('check'), overlap: call('overlap'), mesh: call('mesh'), run: call('run') };
}
