import { createServer } from 'vite';
import { chromium } from 'playwright-core';
const server = await createServer({
  root: '/work/main',
  server: { port: 0, host: '127.0.0.1' },
  logLevel: 'warn',
});
await server.listen();
const url = server.resolvedUrls.local[0];
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: [
    '--no-sandbox',
    '--disable-gpu',
    '--disable-background-networking',
    '--no-first-run',
    '--disable-quic',
    '--disable-component-update',
    '--disable-sync',
  ],
});
const page = await browser.newPage();
page.on('console', (m) => console.log('console:', m.type(), m.text()));
page.on('pageerror', (e) => console.log('pageerror:', e.message));
const q = process.argv[2] ?? '?width=64&height=64&seed=1&spp=8';
await page.goto(url + q);
console.log('isolated', await page.evaluate(() => crossOriginIsolated));
for (let i = 0; i < 10; i++) {
  await page.waitForTimeout(1000);
  console.log(
    await page.evaluate(() => {
      const c = window.__pathwise.controller;
      return JSON.stringify({ ...c.stats(), mode: c.mode });
    }),
  );
}
await browser.close();
await server.close();
