// What the package's tests run against: the native command line (the README's
// build), the built package (web's build) and the shared corpus.
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';

const here = path.dirname(new URL(import.meta.url).pathname);
// The repository (its examples/ and build directories).
export const root = path.resolve(here, '..', '..');

export const cli = process.env.POLYVOL_CLI ?? path.join(root, 'build', 'polyvol');
export const packageDir = process.env.POLYVOL_WEB_PACKAGE ?? path.join(root, 'build-wasm', 'npm');
export const corpusDir = process.env.POLYVOL_CORPUS_DIR ?? path.resolve(root, '..', 'shared', 'corpus');

for (const [what, p] of [['POLYVOL_CLI', cli], ['POLYVOL_WEB_PACKAGE', packageDir], ['POLYVOL_CORPUS_DIR', corpusDir]])
  if (!existsSync(p)) throw new Error(`${what}: ${p} does not exist (build it first: docs/web.md)`);

export const manifest = JSON.parse(readFileSync(path.join(corpusDir, 'manifest.json'), 'utf8'));
export const corpusPath = (entry) => path.join(corpusDir, entry.path);

// `polyvol ARGS` run in dir: {code, stdout, stderr lines}.
export function runCli(args, dir) {
  const r = spawnSync(cli, args, { cwd: dir, encoding: 'utf8', maxBuffer: 1 << 28 });
  if (r.error) throw r.error;
  return { code: r.status, stdout: r.stdout, messages: r.stderr.split('\n').filter((l) => l.length > 0) };
}

export async function loadPackage() {
  return import(path.join(packageDir, 'node.mjs'));
}
