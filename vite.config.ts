import { defineConfig } from 'vite';

/**
 * Cross-origin isolation (COOP + COEP) is what lets the page use
 * SharedArrayBuffer, so the workers can write one shared accumulator. Both
 * the dev server and `vite preview` send the headers.
 */
const isolation = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
};

export default defineConfig({
  server: { headers: isolation },
  preview: { headers: isolation },
  worker: { format: 'es' },
  // Pre-bundled at start-up: discovered later (in the worker) it would make
  // Vite re-optimise and reload the page under a running render.
  // Only the demo page is scanned: examples/embed imports the published
  // package by name (`pathwise`), which exists only in a consumer's install.
  // The decoders of compressed meshes are imported by the model worker only when a model
  // needs them (workers/browser/gltf-browser.ts); listed so that they too are pre-bundled
  // at start-up rather than discovered under a running render; ktx-parse likewise, for the
  // lazy KTX2 chunk (workers/browser/ktx2-browser.ts).
  optimizeDeps: {
    include: [
      'comlink',
      'ktx-parse',
      'meshoptimizer/decoder',
      'draco3dgltf/draco_decoder_gltf_nodejs.js',
    ],
    entries: ['index.html'],
  },
  // dist/cli holds the command line bundle; the web build must not empty it.
  build: { target: 'es2022', outDir: 'dist/web' },
});
