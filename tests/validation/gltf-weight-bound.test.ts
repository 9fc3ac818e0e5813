/**
 * The premise of the per-bounce weight bounds (gltf-bounds.ts: GLTF_WEIGHT_BOUND, or
 * sheenWeightBound for a sheen), checked lobe by lobe: for every drawer of the glTF family
 * (archetypes-gltf.ts), one channel of a BSDF sample's weight f·|cos|/pdf — times
 * etaScale, since the suite's bound counts the (n1/n2)² of refraction apart, per solid —
 * stays at or under its material's bound, over materials drawn by the drawer itself
 * (fixed seeds; 60 materials × 16 directions × 64 samples), loaded by the core's loader
 * and filled as the integrator fills them, with wo on both sides of the surface.
 *
 * The consistency suite only checks the bound on whole paths (the largest BSDF-only
 * sample ≤ V), which is loose; this test sees each lobe's weight directly, so a new lobe
 * whose channel weights exceed the bound fails here by name rather than weakening the
 * suite's variance floor in silence. Deterministic (hashed uniforms): it cannot flake.
 */
import { describe, expect, it } from 'vitest';
import { layeredSample } from '../../src/core/bsdf/gltf-layers.ts';
import { BsdfQuery, BsdfSample } from '../../src/core/bsdf/records.ts';
import { loadGltf } from '../../src/core/gltf/load.ts';
import { HitAttributes, fillGltfShading } from '../../src/core/gltf-material/shading-fill.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import { memoryOptions } from '../helpers/gltf.ts';
import { GLTF_MATERIALS } from './archetypes-gltf.ts';
import { GM_STRIDE } from '../../src/core/gltf-material/material-table.ts';
import { gltfSampleFactors } from './gltf-bounds.ts';
import { Rng } from './rng.ts';

const MATERIALS = 60;
const DIRECTIONS = 16;
const SAMPLES = 64;

describe('GLTF_WEIGHT_BOUND', () => {
  for (const drawer of GLTF_MATERIALS) {
    it(`holds for every sample of the ${drawer.name} drawer`, async () => {
      const g = new Rng(90_001 + drawer.name.length);
      const drawn = Array.from({ length: MATERIALS }, () => drawer.draw(g).material);
      const used = [...new Set(drawn.flatMap((m) => Object.keys(m.extensions ?? {})))];
      const json = {
        asset: { version: '2.0' },
        ...(used.length > 0 ? { extensionsUsed: used } : {}),
        materials: drawn,
        scenes: [{ nodes: [] }],
        scene: 0,
      };
      const model = await loadGltf(
        new TextEncoder().encode(JSON.stringify(json)),
        'm.gltf',
        await memoryOptions(),
      );
      const q = new BsdfQuery();
      const out = new BsdfSample();
      const hit = new HitAttributes();
      let worst = 0;
      let where = '';
      const t = model.materials;
      for (let m = 0; m < MATERIALS; m++) {
        fillGltfShading(t, model.textures, m, hit, q.shading);
        // The bound bsdfSampleBound uses for this material (gltf-bounds.ts).
        const o = m * GM_STRIDE;
        const bound = gltfSampleFactors(t.subarray(o, o + GM_STRIDE)).weight;
        for (let d = 0; d < DIRECTIONS; d++) {
          // wo uniform on the sphere: the back side is the inside of a solid or of a thin wall.
          const z = 1 - 2 * hashToUnit(sampleKey(m, d, 0), 1);
          const phi = 2 * Math.PI * hashToUnit(sampleKey(m, d, 0), 2);
          const s = Math.sqrt(Math.max(0, 1 - z * z));
          for (let k = 0; k < SAMPLES; k++) {
            q.wox = s * Math.cos(phi);
            q.woy = s * Math.sin(phi);
            q.woz = z;
            q.u0 = hashToUnit(sampleKey(m, d, k + 1), 3);
            q.u1 = hashToUnit(sampleKey(m, d, k + 1), 4);
            q.u2 = hashToUnit(sampleKey(m, d, k + 1), 5);
            if (!layeredSample(q.shading, q, out)) continue;
            const w = (Math.max(out.weightR, out.weightG, out.weightB) * out.etaScale) / bound;
            expect(Number.isFinite(w)).toBe(true);
            if (w > worst) {
              worst = w;
              where = `material ${JSON.stringify(drawn[m])}, wo.z ${z.toFixed(3)}`;
            }
          }
        }
      }
      // worst: the largest weight as a fraction of its material's bound.
      expect(worst, where).toBeLessThanOrEqual(1);
    });
  }
});
