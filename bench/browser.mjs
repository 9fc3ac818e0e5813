// What the browser benchmarks share: the demo built for production and served with
// COOP/COEP by `vite preview` (as a deployment serves it), and Debian's Chromium driven
// by playwright-core with the flags that keep a headless, sandbox-less browser off the
// network (tests/helpers/chromium.ts has the tests' copy: the benchmarks run in plain
// Node, which cannot import TypeScript).
import { chromium } from 'playwright-core';
import { build, preview } from 'vite';
import { ROOT } from './lib.mjs';

export const CHROMIUM_ARGS = [
  '--no-sandbox',
  '--disable-gpu',
  '--disable-background-networking',
  '--no-first-run',
  '--disable-quic',
  '--disable-component-update',
  '--disable-sync',
];

export function launchChromium() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium',
    args: CHROMIUM_ARGS,
  });
}

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
