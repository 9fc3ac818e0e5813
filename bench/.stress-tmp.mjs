import { createServer } from 'vite';
import { chromium } from 'playwright-core';
const server = await createServer({
  root: '/work/main',
  server: { port: 0, host: '127.0.0.1', hmr: false },
  logLevel: 'warn',
});
await server.listen();
const url = server.resolvedUrls.local[0];
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu'],
});
for (const q of ['&shared=off', '']) {
  const page = await browser.newPage();
  page.on('console', (m) => {
    if (m.type() === 'error') console.log('console:', m.text());
  });
  page.on('pageerror', (e) => console.log('pageerror:', e.message));
  await page.goto(url + '?width=48&height=40&seed=3&spp=6' + q);
  await page.waitForFunction(() => window.__pathwise?.controller?.stats().spp >= 1);
  const t0 = Date.now();
  for (let i = 0; i < 300; i++) {
    const op = i % 9;
    await page.evaluate(
      async ([op, i]) => {
        const c = window.__pathwise.controller;
        if (op === 0) c.orbit(3, 1);
        if (op === 1) {
          c.beginPreview();
          c.orbit(-2, 0);
        }
        if (op === 2) c.endPreview();
        if (op === 3) c.pause();
        if (op === 4) c.resume();
        if (op === 5) await c.setWorkers(1 + (i % 4));
        if (op === 6) c.reset();
        if (op === 7) c.setBounces(2 + (i % 5));
        if (op === 8) c.setTargetSpp(3 + (i % 7));
      },
      [op, i],
    );
    await page.waitForTimeout(Math.floor(Math.random() * 30));
  }
  await page.evaluate(async () => {
    const c = window.__pathwise.controller;
    c.endPreview();
    c.resume();
    c.setTargetSpp(6);
    await c.setWorkers(3);
  });
  try {
    await page.waitForFunction(() => window.__pathwise.controller.stats().spp >= 6, null, {
      timeout: 30000,
    });
    console.log(
      q,
      'converged after stress',
      (Date.now() - t0) / 1000,
      's',
      await page.evaluate(() =>
        JSON.stringify({
          cam: window.__pathwise.controller.getCamera(),
          b: window.__pathwise.controller.config.maxBounces,
        }),
      ),
    );
  } catch (e) {
    console.log(
      q,
      'STALL',
      await page.evaluate(() => JSON.stringify(window.__pathwise.controller.stats())),
    );
  }
  await page.close();
}
await browser.close();
await server.close();
