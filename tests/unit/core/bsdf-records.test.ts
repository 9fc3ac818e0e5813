/**
 * The record-based BSDF interface: `bsdfEval` reports, beside f, the same
 * density `bsdfPdf` gives (the tracer's MIS weights rely on it), for every
 * material kind and many direction pairs.
 */
import { describe, expect, it } from 'vitest';
import { bsdfEval, bsdfPdf } from '../../../src/core/bsdf/bsdf.ts';
import { compileMaterials } from '../../../src/core/bsdf/materials.ts';
import { BsdfQuery, BsdfValue } from '../../../src/core/bsdf/records.ts';
import { pcgHash } from '../../../src/core/rng/pcg.ts';

const materials = compileMaterials([
  { type: 'diffuse', albedo: [0.5, 0.6, 0.7], emission: [0, 0, 0] },
  { type: 'conductor', color: [0.9, 0.6, 0.3], roughness: 0.05, emission: [0, 0, 0] },
  { type: 'conductor', color: [0.9, 0.6, 0.3], roughness: 0.4, emission: [0, 0, 0] },
  { type: 'conductor', color: [0.9, 0.6, 0.3], roughness: 1, emission: [0, 0, 0] },
  { type: 'conductor', color: [0.9, 0.6, 0.3], roughness: 0, emission: [0, 0, 0] },
  { type: 'dielectric', ior: 1.5, color: [1, 1, 1], roughness: 0, emission: [0, 0, 0] },
]);

describe('bsdfEval', () => {
  it.each([0, 1, 2, 3, 4, 5])('reports the density bsdfPdf gives (material %i)', (m) => {
    const q = new BsdfQuery();
    const f = new BsdfValue();
    let state = 11 + m;
    const rand = (): number => (state = pcgHash(state + 1)) / 4294967296;
    let nonzero = 0;
    for (let i = 0; i < 2000; i++) {
      const set = (z: number): [number, number, number] => {
        const phi = 2 * Math.PI * rand();
        const r = Math.sqrt(Math.max(0, 1 - z * z));
        return [r * Math.cos(phi), r * Math.sin(phi), z];
      };
      [q.wox, q.woy, q.woz] = set(rand() * 1.2 - 0.1);
      [q.wix, q.wiy, q.wiz] = set(rand() * 1.2 - 0.1);
      bsdfEval(materials, m, q, f);
      const pdf = bsdfPdf(materials, m, q);
      expect(f.pdf).toBe(pdf);
      if (pdf > 0) nonzero++;
    }
    // Delta lobes (mirror, glass) have no density; the others must have one.
    if (m <= 3) expect(nonzero).toBeGreaterThan(1000);
    else expect(nonzero).toBe(0);
  });
});
