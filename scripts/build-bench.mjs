// Bundles the benchmarks that import TypeScript (and comlink) into
// dist/bench, self-contained, so that they run on plain Node anywhere (a
// copied tree on another machine has no node_modules).
import { build } from 'esbuild';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
await build({
  absWorkingDir: root,
  entryPoints: {
    'pool-node': 'bench/pool-node.ts',
    'pool-node-worker': 'bench/pool-node-worker.ts',
    inproc: 'bench/inproc.ts',
    rays: 'bench/rays.ts',
    'bvh-build': 'bench/bvh-build.ts',
  },
  outdir: 'dist/bench',
  outExtension: { '.js': '.mjs' },
  bundle: true,
  platform: 'node',
  format: 'esm',
  target: 'node20',
  logLevel: 'warning',
  // esbuild is only imported when no prebuilt worker is given.
  external: ['esbuild'],
  // package.json's sideEffects list is for the library; the benchmark's
  // worker shim is imported for its side effects.
  ignoreAnnotations: true,
});
