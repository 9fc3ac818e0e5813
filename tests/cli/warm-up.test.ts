/**
 * Render workers started before the scene is read and warmed up meanwhile
 * (src/cli/warm-up.ts, workers/node/warm-up.ts): how many warm up, and that a
 * warmed-up pool renders the film bit for bit as one thread does — the
 * warm-up's scenes and film touch nothing of the render, and the stop word
 * ends a warm-up as soon as the real scene is ready (a warm-up left to run
 * its whole budget here would outlast the test's timeout).
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { Film, PathTracer, RenderStats, compileScene, parseScene } from '../../src/core/index.ts';
import { EarlyWorkers, RenderPool } from '../../src/cli/render.ts';
import { warmCount } from '../../src/cli/warm-up.ts';
import { ROOT } from '../helpers/render.ts';

const WORKER = new URL('../../dist/cli/render-worker.js', import.meta.url);
const WIDTH = 48;
const HEIGHT = 40;
const SEED = 3;

describe('early, warmed-up render workers', () => {
  it('warm up only as many as the idle cores hold, one core left to the main thread', () => {
    expect(warmCount(2, 16, 0)).toBe(2);
    expect(warmCount(16, 16, 0.2)).toBe(14);
    expect(warmCount(16, 16, 3.5)).toBe(11);
    expect(warmCount(2, 2, 0)).toBe(1);
    expect(warmCount(2, 2, 4)).toBe(0);
    expect(warmCount(1, 1, 0)).toBe(0);
  });

  it.each(['spheres.json', 'cornell.json'])(
    '%s: a pool taking over warmed-up workers renders the film of one thread, bit for bit',
    async (file) => {
      const scene = parseScene(readFileSync(join(ROOT, 'scenes', file), 'utf8'));
      const job = {
        maxBounces: scene.settings.maxBounces,
        seed: SEED,
        estimator: 'nee-mis' as const,
        sampler: 'sobol' as const,
      };
      // A budget far past the test's timeout: only the stop word can end these warm-ups.
      const early = new EarlyWorkers(2, WORKER, { type: 'warm', job, budgetMs: 600_000 }, 2);
      try {
        // Let the warm-ups get going (the workers start, compile their scenes, trace).
        await new Promise((r) => setTimeout(r, 300));
        const pool = new RenderPool({
          scene,
          width: WIDTH,
          height: HEIGHT,
          ...job,
          threads: 2,
          stripeRows: 2,
          workerUrl: WORKER,
          early,
        });
        try {
          await pool.round(0, 3);
          const film = new Film(WIDTH, HEIGHT);
          const stats = new RenderStats();
          new PathTracer(compileScene(scene), {
            width: WIDTH,
            height: HEIGHT,
            maxBounces: job.maxBounces,
            seed: SEED,
            sampler: 'sobol',
            camera: scene.camera,
          }).renderRows(film, 0, HEIGHT, 0, 3, stats);
          expect(
            Buffer.from(pool.film.buffer as SharedArrayBuffer).equals(
              Buffer.from(film.buffer as ArrayBuffer),
            ),
          ).toBe(true);
          expect(pool.stats.paths).toBe(stats.paths);
          expect(pool.faults.replaced).toBe(0);
        } finally {
          await pool.close();
        }
      } finally {
        await early.close();
      }
    },
  );

  it('a scene that fails to compile ends the workers the pool took over', async () => {
    const scene = parseScene(readFileSync(join(ROOT, 'scenes', 'cornell.json'), 'utf8'));
    // A mesh file never read: compileScene refuses it.
    const broken = {
      ...scene,
      shapes: [
        ...scene.shapes,
        { type: 'mesh' as const, material: 'white', file: 'x.obj', transform: null, data: null },
      ],
    };
    const job = {
      maxBounces: 6,
      seed: 0,
      estimator: 'nee-mis' as const,
      sampler: 'sobol' as const,
    };
    const early = new EarlyWorkers(2, WORKER, null, 0);
    try {
      expect(
        () =>
          new RenderPool({
            scene: broken,
            width: 8,
            height: 8,
            ...job,
            threads: 2,
            workerUrl: WORKER,
            early,
          }),
      ).toThrow(/not read/);
    } finally {
      await early.close();
    }
  });

  it('workers no pool took over are ended by close (a bad scene, say)', async () => {
    const job = {
      maxBounces: 6,
      seed: 0,
      estimator: 'nee-mis' as const,
      sampler: 'sobol' as const,
    };
    const early = new EarlyWorkers(2, WORKER, { type: 'warm', job, budgetMs: 600_000 }, 1);
    await new Promise((r) => setTimeout(r, 100));
    await early.close();
    expect(early.take(0)).toBeNull();
  });
});
