/**
 * Statistical tests of the glTF metallic–roughness BSDF (src/core/bsdf/gltf-pbr.ts):
 *
 * - χ² goodness of fit of `sample` against `pdf` (the harness of
 *   tests/helpers/bsdf-chi2.ts, as in bsdf-chi2.test.ts) over a grid of (metallic,
 *   roughness, transmission, base colour) and of wo, from outside and — for
 *   transmissive materials — from inside. The non-delta samples are binned
 *   on the sphere; delta samples (smooth reflection, refraction) and refused
 *   samples share one pseudo-cell whose expected count is N·(1 − ∫pdf).
 * - The Dirac lobes of smooth materials are picked with the probabilities of
 *   an independent computation of the lobe weights (χ² over three outcomes).
 * - White furnace: the mean sample weight (times the (n2/n1)² that radiance
 *   mode divides out, i.e. the energy) is at most 1 over a grid of
 *   (metallic, roughness, transmission) and of wo, with a tolerance of four
 *   observed standard errors of the mean (false-alarm rate < 1e-4 per case).
 *
 * All with fixed seeds on the core's PCG hash; the χ² tests reject at 1%
 * overall (Šidák-corrected per case).
 */
import { describe, expect, it } from 'vitest';
import { fresnelDielectric, schlickWeight } from '../../src/core/bsdf/fresnel.ts';
import { gltfSample } from '../../src/core/bsdf/gltf-pbr.ts';
import { BsdfQuery, BsdfSample } from '../../src/core/bsdf/records.ts';
import { ShadingParams } from '../../src/core/bsdf/shading.ts';
import { sampleKey } from '../../src/core/rng/pcg.ts';
import {
  bsdfChi2,
  direction,
  expectChi2Fit,
  furnace,
  gltfLobe,
  lobeWidth,
  setSampleQuery,
} from '../helpers/bsdf-chi2.ts';
import { chi2Test } from '../helpers/chi2.ts';

interface Params {
  base: [number, number, number];
  metallic: number;
  roughness: number;
  transmission: number;
  ior?: number;
  specular?: number;
  /** KHR_materials_volume thicknessFactor: these tests are of the solid (> 0) unless told. */
  thickness?: number;
}

const q = new BsdfQuery();

function setParams(p: Params, sp = q.shading): ShadingParams {
  sp.reset();
  [sp.baseR, sp.baseG, sp.baseB] = p.base;
  sp.metallic = p.metallic;
  sp.alpha = p.roughness * p.roughness;
  sp.transmission = p.transmission;
  sp.ior = p.ior ?? 1.5;
  sp.specular = p.specular ?? 1;
  sp.thickness = p.thickness ?? 1;
  return sp;
}

interface Case {
  name: string;
  params: Params;
  thetaO: number;
  /** wo from inside the transmissive solid (wo.z < 0). */
  inside: boolean;
}

const COLOR: [number, number, number] = [0.9, 0.6, 0.3];
const CASES: Case[] = [];
for (const [metallic, transmission] of [
  [0, 0],
  [1, 0],
  [0.5, 0],
  [0, 1],
  [0.3, 0.6],
]) {
  for (const roughness of [0, 0.1, 0.5, 1]) {
    for (const thetaO of [0, 50, 85]) {
      for (const inside of transmission > 0 ? [false, true] : [false]) {
        // Pure smooth metal and smooth glass have no non-delta lobe to test.
        if (roughness === 0 && metallic + transmission >= 1) continue;
        CASES.push({
          name: `metallic ${metallic}, transmission ${transmission}, roughness ${roughness}, wo at ${thetaO}°${inside ? ' inside' : ''}`,
          params: { base: COLOR, metallic, roughness, transmission },
          thetaO,
          inside,
        });
      }
    }
  }
}
/** Šidák-corrected level of each χ² test so that all together reject at 1%. */
const ALPHA = 1 - Math.pow(1 - 0.01, 1 / (CASES.length + 4));
const N = 200_000;

describe('glTF BSDF sample vs pdf: χ² goodness of fit', () => {
  CASES.forEach((c, index) => {
    it(c.name, () => {
      const r = bsdfChi2({
        lobe: gltfLobe,
        sp: setParams(c.params),
        wo: direction(c.thetaO),
        inside: c.inside,
        width: lobeWidth(c.params.roughness ** 2),
        n: N,
        seed: 7000 + index,
      });
      expectChi2Fit(r, ALPHA);
    });
  });

  it('has power: a sampler tested against a neighbouring roughness is rejected', () => {
    const p: Params = { base: COLOR, metallic: 0.5, roughness: 0.3, transmission: 0 };
    const r = bsdfChi2({
      lobe: gltfLobe,
      sp: setParams(p, new ShadingParams()),
      pdfSp: setParams({ ...p, roughness: 0.33 }, new ShadingParams()),
      wo: direction(45),
      width: 0.2,
      n: 100_000,
      seed: 99,
    });
    expect(r.pValue).toBeLessThan(1e-6);
  });
});

/**
 * The lobe weights of a smooth material computed independently of
 * gltf-pbr.ts: probability of the mirror, of the refraction and of the
 * (non-delta) diffuse lobe for wo at cosine cosO.
 */
function smoothLobes(p: Params, cosO: number, inside: boolean): [number, number, number] {
  const ior = p.ior ?? 1.5;
  const f0 = ((ior - 1) / (ior + 1)) ** 2;
  const w = schlickWeight(cosO);
  const fs = f0 + (1 - f0) * w;
  const opaque = (1 - p.metallic) * (1 - p.transmission);
  const diffuse = (opaque * p.base.reduce((a, b) => a + (1 - fs) * b, 0)) / 3;
  const glass = (1 - p.metallic) * p.transmission;
  const fd = fresnelDielectric(cosO, inside ? 1 / ior : ior);
  const total = diffuse + p.metallic + opaque * fs + glass;
  return [
    (p.metallic + opaque * fs + glass * fd) / total,
    (glass * (1 - fd)) / total,
    diffuse / total,
  ];
}

describe('glTF BSDF: smooth (Dirac) lobes', () => {
  const smooth: [string, Params][] = [
    ['smooth plastic', { base: COLOR, metallic: 0, roughness: 0, transmission: 0 }],
    ['smooth half metal', { base: COLOR, metallic: 0.5, roughness: 0, transmission: 0 }],
    ['smooth glass', { base: COLOR, metallic: 0, roughness: 0, transmission: 1 }],
    ['smooth mixture', { base: COLOR, metallic: 0.2, roughness: 0, transmission: 0.5 }],
  ];
  smooth.forEach(([name, p], k) => {
    it(`${name}: mirror, refraction and diffuse are picked with their probabilities`, () => {
      const sp = setParams(p);
      for (const thetaO of [0, 60, 85]) {
        for (const inside of p.transmission > 0 ? [false, true] : [false]) {
          const [x, y, z] = direction(thetaO);
          const woz = inside ? -z : z;
          const [pm, pt, pd] = smoothLobes(p, z, inside);
          const observed = new Float64Array(3);
          const out = new BsdfSample();
          const n = 50_000;
          let refused = 0;
          let notMirror = 0;
          for (let i = 0; i < n; i++) {
            setSampleQuery(q, x, y, woz, sampleKey(500 + k, i, thetaO + (inside ? 1 : 0)));
            if (!gltfSample(sp, q, out)) refused++;
            else if (!out.isDelta) observed[2]++;
            else if (out.wz * woz > 0) {
              if (out.wx !== -x || out.wy !== -y || out.wz !== woz) notMirror++;
              observed[0]++;
            } else observed[1]++;
          }
          expect(refused).toBe(0);
          expect(notMirror).toBe(0);
          const expected = Float64Array.of(n * pm, n * pt, n * pd);
          const r = chi2Test(observed, expected);
          expect(r.impossible).toBeNull();
          expect(r.pValue).toBeGreaterThan(ALPHA);
        }
      }
    });
  });
});

describe('glTF BSDF: white furnace (energy ≤ 1)', () => {
  it("why the diffuse weight is not Appendix B's 1 − F(v·h): that one gains energy", () => {
    // Albedo of a white smooth dielectric (F0 = 0.04) lit at 60°, by
    // midpoint quadrature over the hemisphere of wi: the mirror reflects
    // F(cosθo); the Lambert base is weighted by 1 − F(wo·h) (Appendix B's
    // fresnel_mix) or by (1 − F(cosθo))(1 − F(cosθi)) (gltf-pbr.ts).
    const F = (c: number): number => 0.04 + 0.96 * schlickWeight(c);
    const [ox, oy, oz] = direction(60);
    let literal = 0;
    let coupled = 0;
    const nt = 400;
    const np = 400;
    for (let i = 0; i < nt; i++) {
      const t = ((i + 0.5) / nt) * (Math.PI / 2);
      for (let j = 0; j < np; j++) {
        const p = ((j + 0.5) / np) * 2 * Math.PI;
        const ix = Math.sin(t) * Math.cos(p);
        const iy = Math.sin(t) * Math.sin(p);
        const iz = Math.cos(t);
        const hl = Math.hypot(ox + ix, oy + iy, oz + iz);
        const c = (ox * (ox + ix) + oy * (oy + iy) + oz * (oz + iz)) / hl;
        const dw = Math.sin(t) * (Math.PI / 2 / nt) * ((2 * Math.PI) / np);
        literal += ((1 - F(c)) / Math.PI) * iz * dw;
        coupled += ((1 - F(oz)) * (1 - F(iz)) * iz * dw) / Math.PI;
      }
    }
    expect(F(oz) + literal).toBeGreaterThan(1.02);
    expect(F(oz) + coupled).toBeLessThan(1);
    // …and the sampler agrees with the quadrature of the coupled form.
    const sp = setParams({ base: [1, 1, 1], metallic: 0, roughness: 0, transmission: 0 });
    const out = new BsdfSample();
    let sum = 0;
    let sum2 = 0;
    const n = 100_000;
    for (let i = 0; i < n; i++) {
      setSampleQuery(q, ox, oy, oz, sampleKey(31, i, 0));
      const e = gltfSample(sp, q, out) ? out.weightR : 0;
      sum += e;
      sum2 += e * e;
    }
    const mean = sum / n;
    const se = Math.sqrt((sum2 / n - mean * mean) / n);
    expect(Math.abs(mean - (F(oz) + coupled))).toBeLessThan(4 * se + 1e-4);
  });

  const n = 40_000;
  for (const metallic of [0, 0.5, 1]) {
    for (const transmission of [0, 0.5, 1]) {
      it(`metallic ${metallic}, transmission ${transmission}: every roughness and wo`, () => {
        let worst = -Infinity;
        let where = '';
        let bad = 0;
        for (const roughness of [0, 0.05, 0.3, 0.7, 1]) {
          const sp = setParams({ base: [1, 1, 1], metallic, roughness, transmission });
          for (const thetaO of [0, 30, 60, 80, 89]) {
            for (const inside of transmission > 0 ? [false, true] : [false]) {
              const [x, y, z] = direction(thetaO);
              const stream = roughness * 100 + (inside ? 1 : 0);
              const e = furnace(gltfLobe, sp, [x, y, inside ? -z : z], n, 900 + thetaO, stream);
              bad += e.bad + e.notGrey;
              const [mean] = e.mean;
              const [se] = e.se;
              const excess = (mean - 1) / Math.max(se, 1e-12);
              if (mean - 1 > 4 * se && excess > worst) {
                worst = excess;
                where = `roughness ${roughness}, wo at ${thetaO}°${inside ? ' inside' : ''}: ${mean} ± ${se}`;
              }
            }
          }
        }
        expect(where).toBe('');
        expect(bad).toBe(0);
      });
    }
  }
});
