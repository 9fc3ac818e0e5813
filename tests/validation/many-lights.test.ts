/**
 * The light BVH against an independent reference (issue 23): the room lit by 10,000
 * small emitters (tests/helpers/many-lights-scene.mjs, the scene of
 * bench/many-lights.ts) rendered by Mitsuba 3 (8 parts × 512 spp, its own emitter
 * sampling; many-lights/README.md) and by pathwise with NEE choosing lights through
 * the BVH with splitting, its default (SEEDS independent seeds × SPP). Splitting's
 * probabilities made 5 % too small fail it (55 of the 147 × 3 tests).
 *
 * Per region (the whole image, its quadrants, its 16×16 blocks) and channel, Welch's t
 * on pathwise's per-seed region means against Mitsuba's region mean, whose variance is
 * Σ (per-pixel variance of its mean) / n² on P − 1 = 7 degrees of freedom (a lower
 * bound: the test is conservative there). Each rejects at p < ALPHA / tests
 * (Bonferroni): a correct renderer fails this file with probability ≤ ALPHA = 1e-3.
 * Fixed seeds: it cannot flake.
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { compileScene, decodePfm, parseScene } from '../../src/core/index.ts';
import { manyLights } from '../helpers/many-lights-scene.mjs';
import { imageRegions, renderReplicas, replicaMean } from './replicas.ts';
import { welch } from './stats.ts';

const DIR = fileURLToPath(new URL('./many-lights/', import.meta.url));
const ALPHA = 1e-3;
const SEEDS = 16;
const SPP = 1;
const WIDTH = 128;
const HEIGHT = 96;
const PARTS = 8;

describe('10,000 small emitters: pathwise (light BVH) = Mitsuba 3', () => {
  it('agrees in every region and channel', () => {
    const mean = decodePfm(readFileSync(`${DIR}mitsuba.pfm`));
    const varMean = decodePfm(readFileSync(`${DIR}mitsuba-var.pfm`));
    expect([mean.width, mean.height]).toEqual([WIDTH, HEIGHT]);
    const scene = parseScene(JSON.stringify(manyLights(10_000)));
    const compiled = compileScene(scene);
    expect(compiled.lightBvh()!.count).toBe(10_000);
    const regions = imageRegions(WIDTH, HEIGHT, 16);
    const reps = renderReplicas(
      scene,
      compiled,
      { estimator: 'nee-mis', sampler: 'sobol', spp: SPP },
      Array.from({ length: SEEDS }, (_, k) => 4242 + 31 * k),
      WIDTH,
      HEIGHT,
      regions,
    );
    expect(reps.stats.rejected).toBe(0);
    const alpha = ALPHA / (regions.length * 3);
    const failures: string[] = [];
    let minP = 1;
    regions.forEach((r, ri) => {
      const n = (r.x1 - r.x0) * (r.y1 - r.y0);
      for (let c = 0; c < 3; c++) {
        let m = 0;
        let v = 0;
        for (let y = r.y0; y < r.y1; y++) {
          for (let x = r.x0; x < r.x1; x++) {
            const i = (y * WIDTH + x) * 3 + c;
            m += mean.rgb[i];
            v += varMean.rgb[i];
          }
        }
        const a = replicaMean(reps, ri, c);
        const w = welch(a.mean, a.variance, SEEDS - 1, m / n, v / (n * n), PARTS - 1);
        minP = Math.min(minP, w.p);
        if (!(w.p >= alpha)) {
          failures.push(
            `${r.name} channel ${c}: ${a.mean.toPrecision(5)} vs ${(m / n).toPrecision(5)}, p = ${w.p.toExponential(2)}`,
          );
        }
      }
    });
    expect(failures, `p < ${alpha.toExponential(2)} (smallest p ${minP.toExponential(2)})`).toEqual(
      [],
    );
  });
});
