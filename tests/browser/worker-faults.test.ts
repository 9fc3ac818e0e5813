/**
 * Render workers dying during a render, in Chromium: terminated at random
 * moments, crashing with an uncaught error in the middle of a stripe (some
 * of its rows committed, the rest not), frozen inside a row commit while
 * holding the lock and then terminated (Chromium ends such a worker two
 * seconds later, wherever it stands). The pool must notice, replace the
 * worker and re-render exactly what it had claimed and not finished: the
 * final image must equal the Node core's bit for bit, in shared memory and
 * in transfer mode. The counts (WorkerPool test hooks, worker-deaths.ts)
 * show that each kind of fault really happened.
 */
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { SEED } from './context.ts';
import { bitDifferences, openDemo, readLinear, waitForSpp } from './harness.ts';
import { useDemo } from './context.ts';
import { nodeRender } from './node-reference.ts';
import { C_LOCK } from '../../workers/browser/render-protocol.ts';

const ctx = useDemo();

/** Tall enough for stripes of two rows in shared memory (height / 256), so a stripe can be half written. */
const WIDTH = 24;
const HEIGHT = 512;
const PASSES = 12;
const queryAt = (spp: number) =>
  `width=${WIDTH}&height=${HEIGHT}&seed=${SEED}&spp=${spp}&workers=2`;
const query = queryAt(PASSES);

interface Faults {
  killed: number;
  crashed: number;
  confirmed: number;
  replaced: number;
  reclaimed: number;
  partial: number;
  rowsKept: number;
  journalRepairs: number;
  locksBroken: number;
  tasksResent: number;
  renewals: number;
}

async function faults(page: Page): Promise<Faults> {
  return page.evaluate(() => ({ ...(window as any).__pathwise.faults }));
}

/**
 * Runs the faults of `kinds` in turn, spread over the render: fault i comes
 * once the full film's progress passes a seeded random point of the i-th of
 * n + 1 equal parts, to a running worker chosen at random (seeded too). A
 * crash lands on the worker's next stripe (or task), after its first row:
 * the next fault waits for it. Returns how many of each really happened.
 */
async function faultDuringRender(
  page: Page,
  kinds: ('kill' | 'crash')[],
  seed: number,
): Promise<{ kill: number; crash: number }> {
  return page.evaluate(
    async ({ kinds, seed, passes }) => {
      const w = window as any;
      const c = w.__pathwise.controller;
      const faults = w.__pathwise.faults;
      const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
      let s = seed >>> 0;
      const random = () => {
        s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
        return s / 2 ** 32;
      };
      const done = { kill: 0, crash: 0 };
      // The render is held two passes past the next fault's point (never past
      // `passes`), so that a fast machine cannot finish before every fault has
      // landed; raising the target keeps the samples, as in context-loss.test.ts.
      let target = 0;
      for (let i = 0; i < kinds.length; i++) {
        // Faults fall in the first passes − 3: the hold (two passes on) then always
        // applies, so a crash armed on a loaded machine still finds stripes to claim
        // (spread over all passes, the last came at ~9.5 of 12 and could miss them).
        const at = ((i + 0.5 + 0.5 * random()) / (kinds.length + 1)) * (passes - 3);
        target = Math.max(target, Math.min(passes, Math.ceil(at) + 2));
        c.setTargetSpp(target);
        while (c.progress() < at) await sleep(1 + 4 * random());
        const index = Math.floor(random() * 8);
        // Replacements start in a few milliseconds; until then none may be running.
        if (kinds[i] === 'kill') {
          while (!w.__pathwise.pool().killWorker(index)) await sleep(2);
          done.kill++;
        } else {
          const before = faults.crashed;
          while (!w.__pathwise.pool().crashWorker(index, 1)) await sleep(2);
          // The hold moves on a pass at a time if the render catches up first.
          while (faults.crashed === before && c.stats().spp < passes) {
            if (c.stats().spp >= target && target < passes) c.setTargetSpp(++target);
            await sleep(2);
          }
          if (faults.crashed > before) done.crash++;
        }
      }
      c.setTargetSpp(passes);
      return done;
    },
    { kinds, seed, passes: PASSES },
  );
}

/**
 * Opens the demo and freezes running worker 0 for good inside a row commit
 * (after publishing its row in the journal, before the film copy), holding
 * the lock. The render first stands at 2 passes, its target, so that nothing
 * is left to commit while the hang is armed (a render that ended before the
 * hang landed would never freeze); the target is then raised to PASSES
 * (which keeps the samples), and the worker freezes in its first commit.
 * Returns the page and the worker's token once the lock has stayed with
 * that worker for 250 ms (a live holder keeps it for microseconds).
 */
async function openFrozenInCommit(): Promise<{ page: Page; token: number }> {
  const page = await openDemo(ctx.browser, ctx.url, queryAt(2));
  await waitForSpp(page, 2);
  const token = await page.evaluate(
    async ({ passes, lockIndex }) => {
      const w = window as any;
      const c = w.__pathwise.controller;
      const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
      let token = 0;
      while (!(token = w.__pathwise.pool().hangWorker(0, 2))) await sleep(2);
      // The hang goes to the worker before the kick that the new target sends it.
      c.setTargetSpp(passes);
      const ctrl: Int32Array = c.films.active().ctrl;
      const end = performance.now() + 30_000;
      let since = -1;
      while (performance.now() < end) {
        if (Atomics.load(ctrl, lockIndex) !== token) since = -1;
        else if (since < 0) since = performance.now();
        else if (performance.now() - since >= 250) return token;
        await sleep(2);
      }
      throw new Error(`worker ${token} did not freeze holding the lock (progress ${c.progress()})`);
    },
    { passes: PASSES, lockIndex: C_LOCK },
  );
  return { page, token };
}

/** Waits until every killed or crashed worker is certainly dead and recovered from. */
async function waitForBurials(page: Page, deaths: number): Promise<void> {
  await page.waitForFunction((n) => (window as any).__pathwise.faults.confirmed >= n, deaths, {
    timeout: 30_000,
  });
}

describe('render workers dying mid-render (Chromium)', () => {
  const expected = () => nodeRender('cornell', WIDTH, HEIGHT, SEED, PASSES);

  it('shared memory: 10 workers terminated at random moments, the image is bit-identical', async () => {
    const page = await openDemo(ctx.browser, ctx.url, query);
    const done = await faultDuringRender(page, Array(10).fill('kill'), 11);
    expect(done.kill).toBe(10);
    await waitForSpp(page, PASSES);
    await waitForBurials(page, 10);
    const f = await faults(page);
    expect(f.killed).toBe(10);
    expect(f.replaced).toBe(10);
    // Chromium lets a terminated worker finish the task it is in (the
    // stripe in hand) and stops it at the next yield, so these deaths leave
    // no claim behind (reclaimed stays 0); the crashes and the frozen worker
    // below, and tests/unit/view/pool-faults.test.ts on Node's abrupt threads, do.
    expect(bitDifferences((await readLinear(page)).rgb, expected())).toBe(0);
    console.log(`shared, killed: ${JSON.stringify(f)}`);
    await page.close();
  });

  it('shared memory: 8 workers crashing half way through a stripe, the image is bit-identical', async () => {
    const page = await openDemo(ctx.browser, ctx.url, query);
    const done = await faultDuringRender(page, Array(8).fill('crash'), 23);
    await waitForSpp(page, PASSES);
    await waitForBurials(page, done.crash);
    const f = await faults(page);
    // The render is held until each crash has landed: all eight do.
    expect(done.crash).toBe(8);
    expect(f.crashed).toBe(done.crash);
    // Each crashed worker held a stripe with some of its two rows committed: the
    // crash comes after its first commit. Those rows were kept, the rest re-rendered by
    // another worker. Usually one row; both when the crashing worker had taken over a
    // stripe reclaimed from an earlier crash (its first row already kept, so the crash
    // came after the second), which a fast machine's timing allows now and then.
    expect(f.reclaimed).toBe(f.crashed);
    expect(f.partial).toBe(f.crashed);
    expect(f.rowsKept).toBeGreaterThanOrEqual(f.crashed);
    expect(f.rowsKept).toBeLessThanOrEqual(2 * f.crashed);
    expect(bitDifferences((await readLinear(page)).rgb, expected())).toBe(0);
    console.log(`shared, crashed: ${JSON.stringify(f)}`);
    await page.close();
  });

  it('shared memory: a worker frozen inside a commit, holding the lock, then terminated', async () => {
    const { page, token } = await openFrozenInCommit();
    const waited = await page.evaluate((token) => {
      const w = window as any;
      // A reset meanwhile must not freeze the page on the held lock.
      const t0 = performance.now();
      w.__pathwise.controller.reset();
      const resetMs = performance.now() - t0;
      w.__pathwise.pool().killWorker(0, token);
      return resetMs;
    }, token);
    expect(waited).toBeLessThan(1000);
    await waitForBurials(page, 1);
    await waitForSpp(page, PASSES);
    const f = await faults(page);
    // The reset could not wait for the lock: the film moved to new buffers,
    // and the old block's lock was broken once the worker was known dead.
    expect(f.renewals).toBe(1);
    expect(f.locksBroken).toBe(1);
    expect(bitDifferences((await readLinear(page)).rgb, expected())).toBe(0);
    console.log(`shared, frozen in a commit: ${JSON.stringify(f)}`);
    await page.close();
  });

  it('shared memory: frozen inside a commit and terminated, the commit is finished from the journal', async () => {
    const { page, token } = await openFrozenInCommit();
    await page.evaluate((token) => (window as any).__pathwise.pool().killWorker(0, token), token);
    await waitForBurials(page, 1);
    await waitForSpp(page, PASSES);
    const f = await faults(page);
    expect(f.locksBroken).toBe(1);
    expect(f.journalRepairs).toBe(1);
    expect(bitDifferences((await readLinear(page)).rgb, expected())).toBe(0);
    console.log(`shared, journal repair: ${JSON.stringify(f)}`);
    await page.close();
  });

  it('transfer mode: workers terminated and crashing, the stripes they held go out again', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${query}&shared=off`);
    expect(await page.evaluate(() => (window as any).__pathwise.controller.mode.compute)).toBe(
      'transfer',
    );
    const kinds = [
      'kill',
      'crash',
      'kill',
      'kill',
      'crash',
      'kill',
      'crash',
      'kill',
      'crash',
      'kill',
    ];
    const done = await faultDuringRender(page, kinds as ('kill' | 'crash')[], 5);
    await waitForSpp(page, PASSES);
    const f = await faults(page);
    expect(f.killed).toBe(6);
    expect(done.crash).toBe(4);
    expect(f.crashed).toBe(done.crash);
    // Each crash dropped the task in hand; a kill usually finds one out too.
    expect(f.tasksResent).toBeGreaterThanOrEqual(f.crashed);
    expect(bitDifferences((await readLinear(page)).rgb, expected())).toBe(0);
    console.log(`transfer: ${JSON.stringify(f)}`);
    await page.close();
  });
});
