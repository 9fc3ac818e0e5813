/**
 * Library build of the npm package into dist/lib (the CLI bundle lives in
 * dist/cli and the declarations in dist/types, built by other steps, so only
 * dist/lib is emptied here). Three ESM entries share chunks:
 *   pathwise.js  the main entry: API + element, registers <pathwise-view>
 *   element.js   the same without registering anything
 *   core.js      the DOM-free tracer, for Node and workers
 *   three.js     fromThree: three.js scenes into pathwise scenes (three not bundled:
 *                the bridge reads three's objects without importing it)
 * Dependencies (comlink) are bundled in, so dist/lib also runs straight from
 * a CDN or a plain <script type="module"> with no import map. The render
 * worker is emitted as its own file and found via new URL(…, import.meta.url).
 */
import { defineConfig } from 'vite';

export default defineConfig({
  publicDir: false,
  // Relative, so the worker URL resolves against the package's own files.
  base: './',
  build: {
    outDir: 'dist/lib',
    emptyOutDir: true,
    target: 'es2022',
    sourcemap: true,
    minify: false,
    lib: {
      entry: {
        pathwise: 'src/widget/register.ts',
        element: 'src/widget/index.ts',
        core: 'src/core/index.ts',
        three: 'src/three/index.ts',
      },
      formats: ['es'],
      fileName: (_format, entryName) => `${entryName}.js`,
    },
    rolldownOptions: {
      output: {
        chunkFileNames: 'chunks/[name]-[hash].js',
      },
    },
  },
  worker: {
    format: 'es',
    // A stable name, so hosts that must serve the worker themselves
    // (workerUrl) can point at pathwise/worker without guessing a hash.
    rolldownOptions: {
      output: { entryFileNames: '[name].js' },
    },
  },
});
