/**
 * Independent references (issue 8, deliverable 4): pathwise against
 * Mitsuba 3 and against the native anchor on the reference set
 * (reference-set.ts: the four scenes of the issue and 42 generated ones),
 * rendered by references/make-references.py at 32×24.
 *
 * Each reference is the mean of P parts rendered with different seeds,
 * with its per-pixel variance of the mean s²/P (P − 1 dof per pixel), so
 * its own noise enters the test: a region's variance is Σ var / n², on
 * Satterthwaite's degrees of freedom. pathwise renders SEEDS independent
 * seeds (NEE+MIS, Sobol: the defaults); its variance is their spread.
 * Every region (whole image, quadrants, 8×8 blocks) and channel is a
 * Welch test; each rejects at p < ALPHA / (all tests of the file)
 * (Bonferroni), so a correct renderer fails this file with probability
 * ≤ ALPHA = 1e-3 over fresh seeds. The seeds are fixed: it cannot flake.
 *
 * A reference that is itself wrong for a known reason is listed in
 * KNOWN_REFERENCE_ERRORS with the reason (docs/validation.md); pathwise is
 * then checked against the other one only.
 */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { compileScene, decodePfm, parseScene, type PfmImage } from '../../src/core/index.ts';
import { imageRegions, pilotSegments, renderReplicas, replicaMean } from './replicas.ts';
import { welch } from './stats.ts';

const DIR = fileURLToPath(new URL('./references/', import.meta.url));
const ALPHA = 1e-3;
const SEEDS = 64;
const WIDTH = 32;
const HEIGHT = 24;
/** Work per scene in segment-equivalents (a path = its segments + 2), as in consistency.ts. */
const BUDGET = 1_400_000;
/**
 * Float32 storage and Mitsuba's float32 accumulation: 1e-5 of the value,
 * as in tests/helpers/render.ts (a constant environment of 0.05 reads
 * 0.0500001274 in Mitsuba).
 */
const FLOAT32_REL = 1e-5;

type Renderer = 'mitsuba' | 'native';
interface ManifestEntry {
  scene: string;
  mitsuba: { parts: number; sppPerPart: number; notes: string[] };
  native: { parts: number; sppPerPart: number };
}

const manifest = JSON.parse(readFileSync(`${DIR}references.json`, 'utf8')) as Record<
  string,
  ManifestEntry
>;
const coverage = JSON.parse(readFileSync(`${DIR}set.json`, 'utf8')) as Record<
  string,
  { features?: string[] }
>;

/**
 * References known to be wrong, and why (docs/validation.md): pathwise is
 * compared with the other one only, and the two must still disagree (so
 * the entry is removed once the reference is re-rendered right).
 */
export const KNOWN_REFERENCE_ERRORS: Record<string, { renderer: Renderer; reason: string }> = {};

const names = Object.keys(manifest).sort();
const regions = imageRegions(WIDTH, HEIGHT);
// Per scene and region and channel: pathwise vs Mitsuba, pathwise vs native, Mitsuba vs native.
const comparisons = names.length * 3 * regions.length * 3;
const ALPHA_PER_TEST = ALPHA / comparisons;

function load(name: string, renderer: Renderer, suffix = ''): PfmImage {
  return decodePfm(readFileSync(`${DIR}${name}.${renderer}${suffix}.pfm`));
}

describe('the reference set', () => {
  it('has at least 40 scenes, rendered by both references, covering every light kind and hard case', () => {
    expect(names.length).toBeGreaterThanOrEqual(40);
    expect(names.sort()).toEqual(Object.keys(coverage).sort());
    const features = new Set(Object.values(coverage).flatMap((c) => c.features ?? []));
    for (const f of [
      'sphere-light',
      'quad-light',
      'multiple-lights',
      'power-ratio-1000',
      'tiny-light',
      'large-light',
      'light-near-receiver',
      'huge-receiver',
      'ground-sphere-1e5',
      'grazing',
      'environment',
      'no-environment',
      'camera-in-room',
      'camera-outside',
      'camera-in-glass',
      'aperture',
      'bounces-0',
      'bounces-12',
      'scale-1e-4',
      'scale-1e4',
      'conductor',
      'mirror',
      'dielectric',
    ]) {
      expect(features.has(f), f).toBe(true);
    }
    for (const issue of [
      'issue-sphere-floor',
      'issue-ground-sphere-1e3',
      'issue-ground-sphere-1e5',
      'issue-grazing-quad',
    ]) {
      expect(names).toContain(issue);
    }
  });
});

/** Per region and channel: mean and variance (with dof) of a reference image. */
function referenceRegions(name: string, renderer: Renderer) {
  const ref = load(name, renderer);
  const refVar = load(name, renderer, '-var');
  expect([ref.width, ref.height]).toEqual([WIDTH, HEIGHT]);
  const parts = manifest[name][renderer].parts;
  return regions.map((reg) =>
    [0, 1, 2].map((c) => {
      const n = (reg.x1 - reg.x0) * (reg.y1 - reg.y0);
      let sum = 0;
      let v = 0;
      let v2 = 0;
      for (let y = reg.y0; y < reg.y1; y++) {
        for (let x = reg.x0; x < reg.x1; x++) {
          const i = (y * WIDTH + x) * 3 + c;
          sum += ref.rgb[i];
          v += refVar.rgb[i];
          v2 += refVar.rgb[i] * refVar.rgb[i];
        }
      }
      const mean = sum / n;
      const precision = FLOAT32_REL * Math.abs(mean);
      return {
        mean,
        variance: v / (n * n) + precision * precision,
        // Satterthwaite: a sum of per-pixel variances, each on parts − 1 dof.
        dof: v2 > 0 ? (v * v) / (v2 / (parts - 1)) : Infinity,
      };
    }),
  );
}

function describeFailure(
  label: string,
  region: string,
  c: number,
  a: number,
  b: number,
  w: { t: number; nu: number; p: number },
): string {
  return (
    `${label} ${region} channel ${c}: ${a.toPrecision(6)} vs ${b.toPrecision(6)} ` +
    `(${((a / b - 1) * 100).toFixed(2)} %), t = ${w.t.toFixed(1)}, ν = ${w.nu.toFixed(0)}, p = ${w.p.toExponential(1)}`
  );
}

describe.each(names)('%s', (name) => {
  const entry = manifest[name];
  const known = KNOWN_REFERENCE_ERRORS[name];

  it('has two references that agree with each other (or a known, explained error)', () => {
    const m = referenceRegions(name, 'mitsuba');
    const n = referenceRegions(name, 'native');
    const failures: string[] = [];
    for (let r = 0; r < regions.length; r++) {
      for (let c = 0; c < 3; c++) {
        const w = welch(
          m[r][c].mean,
          m[r][c].variance,
          m[r][c].dof,
          n[r][c].mean,
          n[r][c].variance,
          n[r][c].dof,
        );
        if (!(w.p >= ALPHA_PER_TEST))
          failures.push(
            describeFailure('mitsuba vs native', regions[r].name, c, m[r][c].mean, n[r][c].mean, w),
          );
      }
    }
    if (known) expect(failures.length, `known: ${known.reason}`).toBeGreaterThan(0);
    else expect(failures, `p < ${ALPHA_PER_TEST.toExponential(2)}`).toEqual([]);
  });

  it(`pathwise matches Mitsuba 3 (${entry.mitsuba.parts} × ${entry.mitsuba.sppPerPart} spp) and the native anchor (${entry.native.parts} × ${entry.native.sppPerPart} spp)`, () => {
    const scene = parseScene(readFileSync(`${DIR}${entry.scene}`, 'utf8'));
    const compiled = compileScene(scene);
    const config = { estimator: 'nee-mis', sampler: 'sobol' } as const;
    const perPath = pilotSegments(scene, compiled, config, WIDTH, HEIGHT) + 2;
    let spp = 1;
    while (spp * 2 * perPath * WIDTH * HEIGHT * SEEDS <= BUDGET) spp *= 2;
    const seeds = Array.from({ length: SEEDS }, (_, k) => 424_242 + 7919 * k);
    const ours = renderReplicas(scene, compiled, { ...config, spp }, seeds, WIDTH, HEIGHT, regions);
    expect(ours.stats.rejected).toBe(0);

    const failures: string[] = [];
    for (const renderer of ['mitsuba', 'native'] as const) {
      if (known?.renderer === renderer) continue;
      const ref = referenceRegions(name, renderer);
      for (let r = 0; r < regions.length; r++) {
        for (let c = 0; c < 3; c++) {
          const a = replicaMean(ours, r, c);
          const b = ref[r][c];
          const w = welch(a.mean, a.variance, SEEDS - 1, b.mean, b.variance, b.dof);
          if (!(w.p >= ALPHA_PER_TEST))
            failures.push(
              describeFailure(`pathwise vs ${renderer}`, regions[r].name, c, a.mean, b.mean, w),
            );
        }
      }
    }
    expect(failures, `p < ${ALPHA_PER_TEST.toExponential(2)}`).toEqual([]);
  });
});
