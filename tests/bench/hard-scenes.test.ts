// The hard-scene suite's scenes (bench/hard-scenes.mjs) stay valid pathwise-scene/1 files
// that the native anchor can read too (spheres, quads, the three materials, a constant
// environment), and the committed references are renders of these very scenes: their size,
// finite values, and an image mean that a short render of the scene as generated now
// matches (a scene edited after its reference was made fails here).
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { compileScene, decodePfm, loadScene, type Scene } from '../../src/core/index.ts';
import { nodeSceneFiles } from '../../src/cli/scene-files.ts';
import { HARD_SCENES } from '../../bench/hard-scenes.mjs';
import { referenceMean } from '../helpers/render.ts';
import { renderReplicas } from '../validation/replicas.ts';

const dir = mkdtempSync(path.join(tmpdir(), 'pathwise-hard-scenes-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

/** The scene as the command line loads it: its mesh file (dense.ply) read from `dir`. */
function load(json: Record<string, unknown>): Promise<Scene> {
  return loadScene(JSON.stringify(json), nodeSceneFiles(dir));
}

const lum = (rgb: ArrayLike<number>, i = 0) =>
  0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2];

describe.each(Object.keys(HARD_SCENES))('hard scene %s', (name) => {
  const json = HARD_SCENES[name](dir);

  it('loads, and uses only what the native anchor renders (but for the dense mesh)', async () => {
    const scene = await load(json);
    const kinds = new Set(scene.shapes.map((s) => s.type));
    const allowed = name === 'dense' ? ['quad', 'mesh'] : ['sphere', 'quad'];
    expect([...kinds].every((k) => allowed.includes(k))).toBe(true);
    if (name === 'dense') expect(kinds.has('mesh')).toBe(true);
    const env = json.environment;
    expect(env === undefined || Array.isArray(env)).toBe(true);
  });

  it('has a committed reference of its size, finite and not black', () => {
    const ref = decodePfm(readFileSync(`bench/results/hard/${name}.pfm`));
    const { width, height } = json.settings as { width: number; height: number };
    expect([ref.width, ref.height]).toEqual([width, height]);
    let sum = 0;
    for (const v of ref.rgb) {
      expect(Number.isFinite(v)).toBe(true);
      sum += v;
    }
    expect(sum).toBeGreaterThan(0);
  });

  it("matches its reference's image mean in a short render of the scene as generated", async () => {
    const refMean = lum(referenceMean(decodePfm(readFileSync(`bench/results/hard/${name}.pfm`))));
    // 8 seeds × 16 spp at 32×24 (the same camera: its image mean is the reference's).
    const scene = await load(json);
    const [w, h] = [32, 24];
    const reps = renderReplicas(
      scene,
      compileScene(scene),
      { estimator: 'nee-mis', sampler: 'sobol', spp: 16 },
      [1, 2, 3, 4, 5, 6, 7, 8],
      w,
      h,
      [{ name: 'image', x0: 0, y0: 0, x1: w, y1: h }],
    );
    expect(reps.stats.rejected).toBe(0);
    const means = Array.from({ length: reps.seeds }, (_, k) => lum(reps.means, 3 * k));
    const mean = means.reduce((a, b) => a + b) / means.length;
    const se = Math.sqrt(
      means.reduce((a, x) => a + (x - mean) ** 2, 0) / (means.length - 1) / means.length,
    );
    // Student t with 7 dof at two-sided 1e-4 is 8.0; 0.5 % covers the reference's own
    // noise. A scene edited by 10 % or more fails.
    const detail = `mean ${mean.toFixed(5)} ± ${se.toFixed(5)} against the reference's ${refMean.toFixed(5)}`;
    expect(Math.abs(mean - refMean), detail).toBeLessThan(8 * se + 0.005 * refMean);
  });
});
