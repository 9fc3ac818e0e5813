/**
 * Debian's Chromium driven by playwright-core, shared by the browser and
 * widget tests (Playwright cannot download its own browser here): the path,
 * flags and launch of scripts/chromium.mjs, which the benchmarks use too,
 * with a clear error where the browser is missing.
 */
import { existsSync } from 'node:fs';
import type { Browser } from 'playwright-core';
import { CHROMIUM, CHROMIUM_ARGS, launchChromium as launch } from '../../scripts/chromium.mjs';

export { CHROMIUM, CHROMIUM_ARGS };

export function launchChromium(): Promise<Browser> {
  if (!existsSync(CHROMIUM)) {
    throw new Error(`${CHROMIUM} is missing: apt-get install -y chromium (or set CHROMIUM_PATH)`);
  }
  return launch();
}
