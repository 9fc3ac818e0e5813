// What the browser benchmarks share: the demo built for production and served with
// COOP/COEP by `vite preview` (as a deployment serves it), and Debian's Chromium as the
// tests launch it (scripts/chromium.mjs).
import { build, preview } from 'vite';
import { ROOT } from './lib.mjs';

export { launchChromium } from '../scripts/chromium.mjs';

/** Builds the demo into `outDir` and serves it; resolves to the server and its URL. */
export async function serveBuiltDemo(outDir) {
  await build({ root: ROOT, logLevel: 'error', build: { outDir, emptyOutDir: true } });
  const server = await preview({
    root: ROOT,
    logLevel: 'error',
    build: { outDir },
    preview: { host: '127.0.0.1', port: 0 },
  });
  return { server, url: server.resolvedUrls.local[0] };
}
