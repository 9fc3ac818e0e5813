// Bundles the command line and its worker into dist/cli with esbuild, so
// `pathwise` runs on plain Node without a TypeScript loader.
import { build } from 'esbuild';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
await build({
  absWorkingDir: root,
  entryPoints: {
    pathwise: 'src/cli/main.ts',
    'render-worker': 'workers/node-render-worker.ts',
  },
  outdir: 'dist/cli',
  bundle: true,
  platform: 'node',
  format: 'esm',
  target: 'node20',
  sourcemap: true,
  logLevel: 'warning',
});
