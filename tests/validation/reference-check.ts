/**
 * Independent references (issue 8, deliverable 4; issue 11 §5): pathwise
 * against Mitsuba 3 and against the native anchor on the reference set
 * (reference-set.ts: the four scenes of the issue, 42 generated classic ones
 * and the generated mesh-family ones), rendered by
 * references/make-references.py at 32×24. Shared by references.test.ts
 * (classic), references-mesh.test.ts (meshes and maps) and
 * references-meshed.test.ts (the classic scenes with quads as triangles and
 * a constant environment as a map, `meshedJson`), so vitest runs them on
 * both cores. The native anchor renders no meshes and no maps: a mesh-family
 * scene has the Mitsuba reference alone (and the consistency suite's mesh
 * scenes as its second check); the meshed variant brings triangles and maps
 * before the anchor.
 *
 * Each reference is the mean of P parts rendered with different seeds,
 * with its per-pixel variance of the mean s²/P (P − 1 dof per pixel), so
 * its own noise enters the test: a region's variance is Σ var / n², on
 * Satterthwaite's degrees of freedom. pathwise renders SEEDS independent
 * seeds (NEE+MIS, Sobol: the defaults); its variance is their spread.
 * Every region (whole image, quadrants, 8×8 blocks) and channel is three
 * Welch tests (pathwise vs Mitsuba, pathwise vs native, Mitsuba vs native,
 * each with the rare-sample floor of `compare`), one where Mitsuba is the
 * only reference, two for a meshed variant (pathwise vs each reference);
 * each rejects at p < ALPHA / (all tests of the three files) (Bonferroni),
 * so a correct renderer fails any of them, or all three together, with
 * probability ≤ ALPHA = 1e-3 over fresh seeds. The seeds are fixed: it
 * cannot flake.
 *
 * A reference that is itself wrong for a known reason is listed in
 * KNOWN_REFERENCE_ERRORS with the reason (docs/validation.md); pathwise is
 * then checked against the other one only.
 */
import { readFileSync, statSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import {
  compileScene,
  decodePfm,
  encodePfm,
  parseScene,
  resolveSceneFiles,
  type PfmImage,
  type Scene,
} from '../../src/core/index.ts';
import { bsdfSampleBound } from './consistency.ts';
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
  /** Absent for a scene with meshes or an environment map (the anchor renders neither). */
  native?: { parts: number; sppPerPart: number };
}

export const manifest = JSON.parse(readFileSync(`${DIR}references.json`, 'utf8')) as Record<
  string,
  ManifestEntry
>;
export const coverage = JSON.parse(readFileSync(`${DIR}set.json`, 'utf8')) as Record<
  string,
  { family?: string; features?: string[]; files?: string[] }
>;

/**
 * References known to be wrong, and why (docs/validation.md): pathwise is
 * compared with the other one only, and the two must still disagree (so
 * the entry is removed once the reference is re-rendered right).
 */
export const KNOWN_REFERENCE_ERRORS: Record<string, { renderer: Renderer; reason: string }> = {
  // mitsuba_ref.py caps a huge sphere only when the bounding boxes of everything else lie
  // outside it; here a small sphere's box dips below the ground, so the ground sphere
  // (radius 1e5 × the scene's scale) stays a float32 sphere, whose hit points are off
  // the surface by ~ulp(R): paths self-intersect and the ground reads dark (Mitsuba
  // 0.040 and 0.024 against the native anchor's 0.067 and 0.066 for the image).
  'gen-ground-2006': {
    renderer: 'mitsuba',
    reason: 'uncapped float32 ground sphere of radius 1e5',
  },
  'gen-ground-2009': {
    renderer: 'mitsuba',
    reason: 'uncapped float32 ground sphere of radius 1e5',
  },
};

export const names = Object.keys(manifest).sort();

/** A scene file as JSON (the reference scenes are generated, so their shape is known). */
type SceneFileJson = {
  shapes: { type: string; material: string; corner?: Vec3; u?: Vec3; v?: Vec3 }[];
  environment?: unknown;
};
type Vec3 = [number, number, number];
const sceneJson = (name: string) =>
  JSON.parse(readFileSync(`${DIR}${manifest[name].scene}`, 'utf8')) as SceneFileJson;

/** The file name the meshed variant gives its 1×1 white map (served from memory). */
const MESHED_MAP = 'meshed-constant-environment.pfm';
const hasConstantEnvironment = (json: SceneFileJson) =>
  Array.isArray(json.environment) && (json.environment as number[]).some((x) => x > 0);

/**
 * The meshed variant of a scene: every quad a mesh of two triangles, (c, c+u, c+u+v)
 * and (c, c+u+v, c+v), whose front side is the quad's (cross(u, u+v) = u × v),
 * emissive or not; a constant environment a 1×1 map scaled by its colour. The
 * image is the same, but pathwise renders it with other code: the watertight
 * triangle test and its offsets, emissive triangles sampled by area in NEE, the
 * map's importance sampling and MIS. So the classic scenes' references, the native
 * anchor's among them, check triangles and maps at every scale and at grazing
 * angles, where the mesh family has Mitsuba's reference alone.
 */
export function meshedJson(json: SceneFileJson): SceneFileJson {
  const shapes = json.shapes.map((s) => {
    if (s.type !== 'quad') return s;
    const [c, u, v] = [s.corner!, s.u!, s.v!];
    const p = (a: number, b: number) => [0, 1, 2].map((k) => c[k] + a * u[k] + b * v[k]);
    return {
      type: 'mesh',
      material: s.material,
      positions: [...p(0, 0), ...p(1, 0), ...p(1, 1), ...p(0, 1)],
      indices: [0, 1, 2, 0, 2, 3],
    };
  });
  const environment = hasConstantEnvironment(json)
    ? { type: 'map', file: MESHED_MAP, scale: json.environment }
    : json.environment;
  return { ...json, shapes, environment };
}

/** The classic scenes the meshed variant re-renders: every one with a quad or a constant environment. */
export const meshedNames = names.filter((n) => {
  if (coverage[n]?.family === 'mesh') return false;
  const json = sceneJson(n);
  return json.shapes.some((s) => s.type === 'quad') || hasConstantEnvironment(json);
});

/**
 * The scenes rendered again with adaptive sampling (src/core/film/adaptive.ts,
 * references-adaptive.test.ts): every fourth classic scene, the scenes of issue 8
 * among them, at ADAPTIVE_PASSES passes — the pilot and 48 passes at the map's rates.
 */
export const adaptiveNames = names.filter(
  (n, i) => coverage[n]?.family !== 'mesh' && (n.startsWith('issue-') || i % 4 === 0),
);
const ADAPTIVE_PASSES = 64;

const regions = imageRegions(WIDTH, HEIGHT);
// Per scene, region and channel: pathwise vs Mitsuba, pathwise vs native, Mitsuba vs native;
// pathwise vs Mitsuba alone where the native anchor cannot render the scene; and for each
// scene of the meshed variant, pathwise (meshed) vs Mitsuba and vs native; and for each
// adaptive scene, pathwise (adaptive) vs each reference.
const comparisons =
  names.reduce((n, name) => n + (manifest[name].native ? 3 : 1) * regions.length * 3, 0) +
  meshedNames.length * 2 * regions.length * 3 +
  adaptiveNames.reduce((n, name) => n + (manifest[name].native ? 2 : 1) * regions.length * 3, 0);
const ALPHA_PER_TEST = ALPHA / comparisons;

/**
 * Reads the files a reference scene names from beside it, as the command line does;
 * the meshed variant's white map from memory.
 */
const folderReader = {
  read: async (path: string, maxBytes: number) => {
    if (path === MESHED_MAP) return encodePfm(1, 1, Float32Array.of(1, 1, 1));
    if (statSync(`${DIR}${path}`).size > maxBytes) throw new Error('file too large');
    return new Uint8Array(readFileSync(`${DIR}${path}`));
  },
};

/** The reference scene (or its meshed variant) as pathwise loads it: parsed, its files read. */
async function loadReferenceScene(name: string, meshed = false): Promise<Scene> {
  const text = meshed
    ? JSON.stringify(meshedJson(sceneJson(name)))
    : readFileSync(`${DIR}${manifest[name].scene}`, 'utf8');
  return resolveSceneFiles(parseScene(text), folderReader);
}

/**
 * A bound on any one sample of the three renderers: all are unidirectional
 * path tracers with NEE and power-heuristic MIS, whose light-sampled term
 * at a vertex is β·Le·(f cos/p_bsdf)·p_l p_bsdf/(p_l² + p_bsdf²) ≤ β·Le/2
 * (f cos/p_bsdf ≤ 1 for these BSDFs), plus at most β·Le where a path lands
 * on a light: 1.5 times the BSDF-only bound of consistency.ts.
 */
function bound(scene: Scene): number {
  return 1.5 * bsdfSampleBound(scene);
}

function load(name: string, renderer: Renderer, suffix = ''): PfmImage {
  return decodePfm(readFileSync(`${DIR}${name}.${renderer}${suffix}.pfm`));
}

/** Per region and channel: mean and variance (with dof) of a reference image. */
function referenceRegions(name: string, renderer: Renderer) {
  const ref = load(name, renderer);
  const refVar = load(name, renderer, '-var');
  expect([ref.width, ref.height]).toEqual([WIDTH, HEIGHT]);
  const parts = manifest[name][renderer]!.parts;
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
        samples: n * parts * manifest[name][renderer]!.sppPerPart,
        variance: v / (n * n) + precision * precision,
        // Satterthwaite: a sum of per-pixel variances, each on parts − 1 dof.
        dof: v2 > 0 ? (v * v) / (v2 / (parts - 1)) : Infinity,
      };
    }),
  );
}

interface Estimate {
  mean: number;
  variance: number;
  dof: number;
  samples: number;
}

/**
 * Welch's test of two renders whose every sample lies in [0, V]. Heavy
 * tails (a tiny bright light seen directly or through glass) make the side
 * with fewer samples miss rare huge samples and read low with a small
 * spread; as in consistency.ts, the side that reads low by Δ gets the
 * variance floor ΔV/N (missed samples of size ≤ V), which rejects only when
 * ≥ z² ≈ 30 expected rare samples would all have been missed.
 */
function compare(a: Estimate, b: Estimate, bound: number) {
  const floor = (low: Estimate, high: Estimate) => ((high.mean - low.mean) * bound) / low.samples;
  let [va, dfa, vb, dfb] = [a.variance, a.dof, b.variance, b.dof];
  if (a.mean < b.mean && floor(a, b) > va) [va, dfa] = [floor(a, b), Infinity];
  if (b.mean < a.mean && floor(b, a) > vb) [vb, dfb] = [floor(b, a), Infinity];
  return welch(a.mean, va, dfa, b.mean, vb, dfb);
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

/**
 * Registers the reference tests of the scenes `list` (names of the manifest), as they
 * are or, with `meshed`, their meshed variant (meshedJson) against the same references.
 */
export function referenceSuite(list: string[], meshed = false, adaptive = false): void {
  const label = meshed ? '%s, meshed' : adaptive ? '%s, adaptive' : '%s';
  describe.each(list)(label, (name) => referenceTests(name, meshed, adaptive));
}

function referenceTests(name: string, meshed: boolean, adaptive: boolean): void {
  const entry = manifest[name];
  const known = KNOWN_REFERENCE_ERRORS[name];

  // Only where there are two references (a mesh-family scene has Mitsuba's alone), and
  // once per scene (not again for its meshed variant).
  if (entry.native && !meshed && !adaptive) {
    it('has two references that agree with each other (or a known, explained error)', async () => {
      const V = bound(await loadReferenceScene(name));
      const m = referenceRegions(name, 'mitsuba');
      const n = referenceRegions(name, 'native');
      const failures: string[] = [];
      for (let r = 0; r < regions.length; r++) {
        for (let c = 0; c < 3; c++) {
          const w = compare(m[r][c], n[r][c], V);
          if (!(w.p >= ALPHA_PER_TEST))
            failures.push(
              describeFailure(
                'mitsuba vs native',
                regions[r].name,
                c,
                m[r][c].mean,
                n[r][c].mean,
                w,
              ),
            );
        }
      }
      if (known) expect(failures.length, `known: ${known.reason}`).toBeGreaterThan(0);
      else expect(failures, `p < ${ALPHA_PER_TEST.toExponential(2)}`).toEqual([]);
    });
  }

  const what = entry.native
    ? `Mitsuba 3 (${entry.mitsuba.parts} × ${entry.mitsuba.sppPerPart} spp) and the native anchor (${entry.native.parts} × ${entry.native.sppPerPart} spp)`
    : `Mitsuba 3 (${entry.mitsuba.parts} × ${entry.mitsuba.sppPerPart} spp; the native anchor renders no meshes or maps)`;
  const how = meshed
    ? ', its quads as triangles and its environment a map,'
    : adaptive
      ? ` with adaptive sampling (${ADAPTIVE_PASSES} passes)`
      : '';
  it(`pathwise${how} matches ${what}`, async () => {
    const loaded = await loadReferenceScene(name, meshed);
    const V = bound(loaded);
    const compiled = compileScene(loaded);
    const config = { estimator: 'nee-mis', sampler: 'sobol' } as const;
    const perPath = pilotSegments(loaded, compiled, config, WIDTH, HEIGHT) + 2;
    let spp = 1;
    while (spp * 2 * perPath * WIDTH * HEIGHT * SEEDS <= BUDGET) spp *= 2;
    if (adaptive) spp = ADAPTIVE_PASSES;
    const base = meshed ? 515_151 : adaptive ? 616_161 : 424_242;
    const seeds = Array.from({ length: SEEDS }, (_, k) => base + 7919 * k);
    const ours = renderReplicas(
      loaded,
      compiled,
      { ...config, spp, adaptive },
      seeds,
      WIDTH,
      HEIGHT,
      regions,
    );
    expect(ours.stats.rejected).toBe(0);

    const failures: string[] = [];
    for (const renderer of ['mitsuba', 'native'] as const) {
      if (known?.renderer === renderer || !entry[renderer]) continue;
      const ref = referenceRegions(name, renderer);
      for (let r = 0; r < regions.length; r++) {
        for (let c = 0; c < 3; c++) {
          const m = replicaMean(ours, r, c);
          const a = { ...m, dof: SEEDS - 1, samples: ours.samples[r] };
          const b = ref[r][c];
          const w = compare(a, b, V);
          if (!(w.p >= ALPHA_PER_TEST))
            failures.push(
              describeFailure(`pathwise vs ${renderer}`, regions[r].name, c, a.mean, b.mean, w),
            );
        }
      }
    }
    expect(failures, `p < ${ALPHA_PER_TEST.toExponential(2)}`).toEqual([]);
  });
}
