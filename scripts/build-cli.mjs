// Bundles the command line and its workers into dist/cli with esbuild, so
// `pathwise` runs on plain Node without a TypeScript loader.
//
// The command line is split (esbuild's code splitting): what a scene of
// spheres, quads and meshes needs is in pathwise.js; the glTF loader
// (glTF-Transform, image decoders, MikkTSpace: most of the code) is in
// dist/cli/chunks, imported only when a scene names a model, so a render
// does not compile 800 KB of JavaScript it will not run. Each worker (the
// render worker; the denoiser's, src/cli/denoise-pool.ts) is one file of its own.
import { build } from 'esbuild';
import { rmSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
const common = {
  absWorkingDir: root,
  outdir: 'dist/cli',
  bundle: true,
  platform: 'node',
  format: 'esm',
  target: 'node20',
  sourcemap: true,
  logLevel: 'warning',
};
// Chunk names carry a hash: clear those of earlier builds.
rmSync(new URL('../dist/cli/chunks', import.meta.url), { recursive: true, force: true });
await Promise.all([
  build({
    ...common,
    entryPoints: { pathwise: 'src/cli/main.ts', command: 'src/cli/command.ts' },
    splitting: true,
    chunkNames: 'chunks/[name]-[hash]',
  }),
  build({ ...common, entryPoints: { 'render-worker': 'workers/node/render-worker.ts' } }),
  build({ ...common, entryPoints: { 'denoise-worker': 'workers/node/denoise-worker.ts' } }),
]);
