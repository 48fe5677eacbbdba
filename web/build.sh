#!/usr/bin/env bash
# The WebAssembly core, the npm package (build-wasm/npm) and the page
# (build-wasm/page), with Debian's Emscripten 3.1.6 and web/'s npm
# dependencies (three, fflate, puppeteer-core, from the lockfile). docs/web.md.
# Then `npm --prefix web test` runs the package's and the browser's tests.
set -euo pipefail
cd "$(dirname "$0")/.."
export NODE_PATH=/usr/share/nodejs  # Emscripten's JS optimizer needs Debian's node-acorn
npm ci --prefix web --no-audit --no-fund --loglevel=error
emcmake cmake -S web -B build-wasm -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-wasm -j2
