/**
 * Statistical tests of KHR_materials_anisotropy and KHR_materials_iridescence
 * inside the glTF BSDF (src/core/bsdf/gltf-pbr.ts with gltf-anisotropy.ts and
 * gltf-iridescence.ts), modelled on gltf-bsdf-chi2.test.ts:
 *
 * - χ² goodness of fit of `sample` against `pdf` over a grid of (strength,
 *   rotation, roughness, metallic, transmission) and of (iridescence, film
 *   index, thickness), from outside and, for glass, from inside; the sample
 *   weights and densities must equal f·cos/pdf and `pdf` to 1e-9;
 * - reciprocity: f(wo, wi) = f(wi, wo) to 1e-9 relative;
 * - white furnace: the mean sample weight of a white material, per channel,
 *   is at most 1 + 4 observed standard errors (false-alarm rate < 1e-4 per
 *   case) over a parameter grid;
 * - reductions: strength 0 and iridescence 0 are bit-identical to the plain
 *   material whatever the other fields of the extension hold; film
 *   thickness 0 is the plain Fresnel to rounding.
 *
 * Fixed seeds on the core's PCG hash; the χ² tests reject at 1% overall
 * (Šidák-corrected per case).
 */
import { describe, expect, it } from 'vitest';
import { gltfEval, gltfSample } from '../../src/core/bsdf/gltf-pbr.ts';
import { BsdfQuery, BsdfSample, BsdfValue } from '../../src/core/bsdf/records.ts';
import { ShadingParams } from '../../src/core/bsdf/shading.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import {
  bsdfChi2,
  DEG,
  direction,
  evalBothWays,
  expectChi2Fit,
  furnace,
  gltfLobe,
  lobeWidth,
  relErr,
} from '../helpers/bsdf-chi2.ts';

interface Params {
  base?: [number, number, number];
  metallic: number;
  roughness: number;
  transmission?: number;
  strength?: number;
  rotation?: number;
  iridescence?: number;
  filmIor?: number;
  thickness?: number;
}

const q = new BsdfQuery();
const COLOR: [number, number, number] = [0.9, 0.6, 0.3];

function setParams(p: Params, sp = q.shading): ShadingParams {
  sp.reset();
  [sp.baseR, sp.baseG, sp.baseB] = p.base ?? COLOR;
  sp.metallic = p.metallic;
  sp.alpha = p.roughness * p.roughness;
  sp.transmission = p.transmission ?? 0;
  sp.anisotropy = p.strength ?? 0;
  sp.anisotropyCos = Math.cos(p.rotation ?? 0);
  sp.anisotropySin = Math.sin(p.rotation ?? 0);
  sp.iridescence = p.iridescence ?? 0;
  sp.iridescenceIor = p.filmIor ?? 1.3;
  sp.iridescenceThickness = p.thickness ?? 400;
  // shading-fill.ts's rule: an anisotropic smooth surface gets the smallest α.
  if (sp.anisotropy > 0 && sp.alpha === 0) sp.alpha = 1e-6;
  return sp;
}

interface Case {
  name: string;
  p: Params;
  thetaO: number;
  inside: boolean;
}
const CASES: Case[] = [];
const add = (p: Params, thetaO: number, inside = false): void => {
  CASES.push({
    name: `${JSON.stringify(p)}, wo at ${thetaO}°${inside ? ' inside' : ''}`,
    p,
    thetaO,
    inside,
  });
};
for (const [metallic, transmission] of [
  [1, 0],
  [0, 0],
  [0, 1],
]) {
  for (const [roughness, strength, rotation] of [
    [0.1, 1, 0],
    [0.5, 0.5, 1.1],
    [0.3, 0.8, -2],
  ]) {
    for (const thetaO of [30, 75]) {
      add({ metallic, transmission, roughness, strength, rotation }, thetaO);
      if (transmission > 0 && thetaO === 30)
        add({ metallic, transmission, roughness, strength, rotation }, thetaO, true);
    }
  }
}
for (const [metallic, iridescence, filmIor, thickness, thetaO] of [
  [0, 1, 1.3, 400, 60],
  [1, 1, 1.8, 250, 0],
  [0.5, 0.6, 1.3, 700, 30],
]) {
  add({ metallic, roughness: 0.4, iridescence, filmIor, thickness }, thetaO);
}
add({ metallic: 0.5, roughness: 0.3, strength: 0.7, rotation: 0.5, iridescence: 1 }, 45);
add({ metallic: 0, transmission: 1, roughness: 0.3, iridescence: 1, filmIor: 1.8 }, 50);
add({ metallic: 0, transmission: 1, roughness: 0.3, iridescence: 1, filmIor: 1.8 }, 50, true);
add({ metallic: 0, roughness: 0, iridescence: 1, thickness: 300 }, 40);

const ALPHA = 1 - Math.pow(1 - 0.01, 1 / CASES.length);
const N = 60_000;

describe('glTF BSDF with anisotropy and iridescence: sample vs pdf (χ²)', () => {
  CASES.forEach((c, index) => {
    it(c.name, () => {
      const sp = setParams(c.p);
      const r = bsdfChi2({
        lobe: gltfLobe,
        sp,
        wo: direction(c.thetaO),
        inside: c.inside,
        width: lobeWidth(sp.alpha + (1 - sp.alpha) * sp.anisotropy ** 2),
        n: N,
        seed: 8100 + index,
        quadrature: sp.alpha < 0.05 && sp.anisotropy > 0 ? 24 : 8,
      });
      expectChi2Fit(r, ALPHA);
    });
  });

  it('has power: the anisotropic sampler tested against the density of a rotated direction is rejected', () => {
    const p: Params = { metallic: 1, roughness: 0.3, strength: 0.8, rotation: 0.3 };
    // The refusals (~15% here) are expected at N·(1 − ∫pdf) like every case's: expected
    // at 0, they alone would reject even the sampler's own density.
    const r = bsdfChi2({
      lobe: gltfLobe,
      sp: setParams(p, new ShadingParams()),
      pdfSp: setParams({ ...p, rotation: 0.45 }, new ShadingParams()),
      wo: direction(45),
      width: 2,
      n: 100_000,
      seed: 98,
    });
    expect(r.pValue).toBeLessThan(1e-6);
  });
});

describe('glTF BSDF with anisotropy and iridescence: reciprocity', () => {
  it('f(wo, wi) = f(wi, wo) over a parameter grid', () => {
    const f1 = new BsdfValue();
    const f2 = new BsdfValue();
    let worst = 0;
    let where = '';
    let n = 0;
    for (const [metallic, transmission] of [
      [0, 0],
      [0.5, 0],
      [1, 0],
      [0.2, 0.6],
    ]) {
      for (const roughness of [0.05, 0.4, 1]) {
        for (const [strength, iridescence] of [
          [0.7, 0],
          [1, 0],
          [0, 1],
          [0.5, 0.8],
        ]) {
          const sp = setParams({
            metallic,
            transmission,
            roughness,
            strength,
            rotation: 0.9,
            iridescence,
            thickness: 350,
          });
          for (let i = 0; i < 200; i++) {
            const key = sampleKey(77, i, n);
            const a = Math.acos(hashToUnit(key, 0));
            const b = Math.acos(hashToUnit(key, 1));
            // Both on one side; for glass also both inside (z < 0).
            const side = transmission > 0 && i % 2 === 1 ? -1 : 1;
            const [ox, oy, zo] = direction(a / DEG, 2 * Math.PI * hashToUnit(key, 2));
            const [ix, iy, zi] = direction(b / DEG, 2 * Math.PI * hashToUnit(key, 3));
            const wo: [number, number, number] = [ox, oy, side * zo];
            const e = evalBothWays(gltfLobe, sp, wo, [ix, iy, side * zi], f1, f2);
            if (e > worst) {
              worst = e;
              where = `metallic ${metallic}, transmission ${transmission}, roughness ${roughness}, strength ${strength}, iridescence ${iridescence}`;
            }
          }
          n++;
        }
      }
    }
    expect(worst, where).toBeLessThan(1e-9);
  });
});

describe('glTF BSDF with anisotropy and iridescence: white furnace (energy ≤ 1)', () => {
  const run = (p: Params, thetaO: number, n: number, seed: number): string => {
    const sp = setParams({ ...p, base: [1, 1, 1] });
    const { mean, se, bad } = furnace(gltfLobe, sp, direction(thetaO), n, seed, thetaO);
    if (bad > 0) return `${bad} samples of non-finite or negative weight`;
    for (let k = 0; k < 3; k++) {
      if (mean[k] - 1 > 4 * se[k]) return `channel ${k}: ${mean[k]} ± ${se[k]}`;
    }
    return '';
  };
  it('anisotropy: (metallic, transmission) × roughness × strength × rotation × wo', () => {
    const failures: string[] = [];
    let seed = 0;
    for (const [metallic, transmission] of [
      [0, 0],
      [1, 0],
      [0, 1],
    ])
      for (const roughness of [0, 0.3, 0.7])
        for (const strength of [0.5, 1])
          for (const rotation of [0, 2])
            for (const thetaO of [0, 60, 85]) {
              const p = { metallic, transmission, roughness, strength, rotation };
              const r = run(p, thetaO, 8_000, 300 + seed++);
              if (r !== '') failures.push(`${JSON.stringify(p)} at ${thetaO}°: ${r}`);
            }
    expect(failures).toEqual([]);
  });
  it('iridescence: (metallic, transmission) × roughness × film index × thickness × wo', () => {
    const failures: string[] = [];
    let seed = 0;
    for (const [metallic, transmission] of [
      [0, 0],
      [1, 0],
      [0, 1],
      [0.2, 0.5],
    ])
      for (const roughness of [0, 0.3, 0.7])
        for (const filmIor of [1.3, 2])
          for (const thickness of [150, 600])
            for (const thetaO of [0, 70]) {
              const p = { metallic, transmission, roughness, iridescence: 1, filmIor, thickness };
              const r = run(p, thetaO, 5_000, 600 + seed++);
              if (r !== '') failures.push(`${JSON.stringify(p)} at ${thetaO}°: ${r}`);
            }
    expect(failures).toEqual([]);
  });
});

describe('glTF BSDF: reductions of anisotropy and iridescence', () => {
  const f1 = new BsdfValue();
  const f2 = new BsdfValue();
  const s1 = new BsdfSample();
  const s2 = new BsdfSample();
  /** Eval and sample of two parameter sets at the same queries: exact, or to `tol`. */
  const compare = (a: Params, b: Params, tol: number): number => {
    let worst = 0;
    for (let i = 0; i < 300; i++) {
      const key = sampleKey(55, i, 0);
      const [ox, oy, oz] = direction(89 * hashToUnit(key, 0), 6 * hashToUnit(key, 1));
      const [ix, iy, iz] = direction(89 * hashToUnit(key, 2), 6 * hashToUnit(key, 3));
      const u = [hashToUnit(key, 4), hashToUnit(key, 5), hashToUnit(key, 6)];
      const one = (p: Params, f: BsdfValue, s: BsdfSample): boolean => {
        const sp = setParams(p);
        Object.assign(q, {
          wox: ox,
          woy: oy,
          woz: oz,
          wix: ix,
          wiy: iy,
          wiz: iz,
          u0: u[0],
          u1: u[1],
          u2: u[2],
        });
        gltfEval(sp, q, f);
        return gltfSample(sp, q, s);
      };
      const ok1 = one(a, f1, s1);
      const ok2 = one(b, f2, s2);
      if (ok1 !== ok2) worst = Infinity;
      const pairs: [number, number][] = [
        [f1.r, f2.r],
        [f1.g, f2.g],
        [f1.b, f2.b],
        [f1.pdf, f2.pdf],
      ];
      if (ok1) {
        pairs.push([s1.wx, s2.wx], [s1.wy, s2.wy], [s1.wz, s2.wz], [s1.weightR, s2.weightR]);
        pairs.push([s1.weightG, s2.weightG], [s1.weightB, s2.weightB], [s1.pdf, s2.pdf]);
      }
      for (const [x, y] of pairs) {
        if (tol === 0) {
          if (!Object.is(x, y)) worst = Infinity;
        } else worst = Math.max(worst, relErr(x, y));
      }
    }
    return worst;
  };
  const bases: Params[] = [
    { metallic: 0, roughness: 0.4 },
    { metallic: 1, roughness: 0.2 },
    { metallic: 0.3, roughness: 0 },
    { metallic: 0.2, roughness: 0.6, transmission: 0.7 },
  ];
  it('strength 0 is the isotropic material bit for bit, whatever the direction', () => {
    for (const b of bases) expect(compare(b, { ...b, strength: 0, rotation: 1.3 }, 0)).toBe(0);
  });
  it('iridescence 0 is the plain material bit for bit, whatever the film', () => {
    for (const b of bases)
      expect(compare(b, { ...b, iridescence: 0, filmIor: 2.2, thickness: 123 }, 0)).toBe(0);
  });
  it('a film of thickness 0 (or of index 1) is the plain Fresnel to rounding', () => {
    for (const b of bases) {
      expect(compare(b, { ...b, iridescence: 1, thickness: 0 }, 1)).toBeLessThan(1e-12);
      expect(compare(b, { ...b, iridescence: 0.7, filmIor: 1, thickness: 500 }, 1)).toBeLessThan(
        1e-12,
      );
    }
  });
});
