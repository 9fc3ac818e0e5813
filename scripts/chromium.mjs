// Debian's Chromium driven by playwright-core (Playwright cannot download its own
// browser here), as the browser tests, the benchmarks and the corpus script all launch
// it. The flags keep a headless, sandbox-less Chromium from reaching out to the network;
// with them WebGL2 is ANGLE on SwiftShader (software). Plain JavaScript, so that plain
// Node scripts and the TypeScript tests (tests/helpers/chromium.ts) import the one list.
import { chromium } from 'playwright-core';

export const CHROMIUM = process.env.CHROMIUM_PATH ?? '/usr/bin/chromium';

export const CHROMIUM_ARGS = [
  '--no-sandbox',
  '--disable-gpu',
  '--disable-background-networking',
  '--no-first-run',
  '--disable-quic',
  '--disable-component-update',
  '--disable-sync',
];

/** Launches CHROMIUM with CHROMIUM_ARGS. */
export function launchChromium() {
  return chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS });
}
