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
  // ktx-parse: imported by the lazy KTX2 chunk (workers/browser/ktx2-browser.ts).
  optimizeDeps: { include: ['comlink', 'ktx-parse'], entries: ['index.html'] },
  // dist/cli holds the command line bundle; the web build must not empty it.
  build: { target: 'es2022', outDir: 'dist/web' },
});
