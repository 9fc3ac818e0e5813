/**
 * Statistical tests of the layered glTF material (src/core/bsdf/gltf-layers.ts:
 * clearcoat over sheen over the base of gltf-pbr.ts) and of its two lobes, modelled on
 * gltf-bsdf-chi2.test.ts:
 *
 * - χ² of `layeredSample` against `layeredPdf` over a grid of coats (factor, roughness,
 *   tilted normal), sheens (colour, roughness), bases (metallic, roughness, glass) and wo;
 *   delta samples (smooth coat, smooth base) and refusals share one pseudo-cell of
 *   expected count N·(1 − ∫pdf). Every non-delta sample's weight must be f·cos/pdf.
 * - Reciprocity: f(wo, wi) = f(wi, wo) to 1e-12 on random pairs, for every case.
 * - White furnace: the mean weight of every channel is at most 1 + 4 observed
 *   standard errors (false-alarm rate < 1e-4 per case) over the grids of the plan:
 *   coat c ∈ {.5, 1} × coat roughness {0, .3, .7, 1} × white base metallic {0, 1} ×
 *   roughness {0, .3, 1}, and sheen colour {.5, 1, (1, .5, 0)} × sheen roughness
 *   {.05, .3, .6, 1} × white diffuse or white metal, each at 5 angles; and a coat and a
 *   sheen over white glass, seen from outside (energy: weight × etaScale).
 * - Reductions: clearcoat 0 and black sheen are the base bit for bit (eval, pdf,
 *   sample); unlit scatters nothing.
 *
 * Fixed seeds on the core's PCG hash; the χ² tests reject at 1% overall (Šidák).
 */
import { describe, expect, it } from 'vitest';
import { layeredEval, layeredPdf, layeredSample } from '../../src/core/bsdf/gltf-layers.ts';
import { gltfEval, gltfPdf, gltfSample } from '../../src/core/bsdf/gltf-pbr.ts';
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
  lobeWidth,
  type Lobe,
} from '../helpers/bsdf-chi2.ts';

interface Params {
  base?: [number, number, number];
  metallic: number;
  roughness: number;
  transmission?: number;
  clearcoat?: number;
  coatRoughness?: number;
  coatNormal?: [number, number, number];
  sheen?: [number, number, number];
  sheenRoughness?: number;
  /** χ² sample count, when not N_DEFAULT. */
  samples?: number;
}

const q = new BsdfQuery();

function setParams(p: Params, sp = q.shading): ShadingParams {
  sp.reset();
  [sp.baseR, sp.baseG, sp.baseB] = p.base ?? [0.9, 0.6, 0.3];
  sp.metallic = p.metallic;
  sp.alpha = p.roughness * p.roughness;
  sp.transmission = p.transmission ?? 0;
  sp.clearcoat = p.clearcoat ?? 0;
  sp.clearcoatAlpha = (p.coatRoughness ?? 0) ** 2;
  if (p.coatNormal) {
    const [x, y, z] = p.coatNormal;
    const l = Math.hypot(x, y, z);
    sp.ccnx = x / l;
    sp.ccny = y / l;
    sp.ccnz = z / l;
  }
  [sp.sheenR, sp.sheenG, sp.sheenB] = p.sheen ?? [0, 0, 0];
  sp.sheenRoughness = p.sheenRoughness ?? 0;
  return sp;
}

const LAYERED: Lobe = { sample: layeredSample, pdf: layeredPdf, eval: layeredEval };

const SHEEN: [number, number, number] = [0.9, 0.6, 0.3];
const CASES: [string, Params][] = [
  [
    'rough coat on rough plastic',
    { metallic: 0, roughness: 0.5, clearcoat: 1, coatRoughness: 0.3 },
  ],
  ['half coat on rough metal', { metallic: 1, roughness: 0.6, clearcoat: 0.5, coatRoughness: 0.7 }],
  ['smooth coat on rough plastic', { metallic: 0, roughness: 0.5, clearcoat: 1, coatRoughness: 0 }],
  // Mostly the base's mirror (a delta): more samples, for enough in the coat's cells.
  [
    'rough coat on smooth metal',
    { metallic: 1, roughness: 0, clearcoat: 1, coatRoughness: 0.4, samples: 300_000 },
  ],
  [
    'tilted rough coat',
    { metallic: 0, roughness: 0.7, clearcoat: 1, coatRoughness: 0.5, coatNormal: [0.3, -0.2, 1] },
  ],
  [
    'rough coat over sheen on rough glass (from outside)',
    {
      metallic: 0,
      roughness: 0.3,
      transmission: 1,
      clearcoat: 1,
      coatRoughness: 0.5,
      sheen: SHEEN,
      sheenRoughness: 0.5,
    },
  ],
  ['sharp sheen on plastic', { metallic: 0, roughness: 0.5, sheen: SHEEN, sheenRoughness: 0.1 }],
  ['rough sheen on metal', { metallic: 1, roughness: 0.3, sheen: SHEEN, sheenRoughness: 1 }],
  ['white sheen', { metallic: 0, roughness: 1, sheen: [1, 1, 1], sheenRoughness: 0.5 }],
  [
    'coat over sheen over plastic',
    {
      metallic: 0,
      roughness: 0.4,
      clearcoat: 0.8,
      coatRoughness: 0.2,
      sheen: SHEEN,
      sheenRoughness: 0.4,
    },
  ],
];
const THETAS = [0, 50, 85];
const ALPHA = 1 - Math.pow(1 - 0.01, 1 / (CASES.length * THETAS.length));
const N_DEFAULT = 60_000;

describe('layered glTF BSDF: sample vs pdf (χ²)', () => {
  CASES.forEach(([name, p], index) => {
    for (const thetaO of THETAS) {
      it(`${name}, wo at ${thetaO}°`, () => {
        const alphas = [p.roughness ** 2, (p.coatRoughness ?? 0) ** 2].filter((a) => a > 0);
        const r = bsdfChi2({
          lobe: LAYERED,
          sp: setParams(p),
          wo: direction(thetaO),
          width: lobeWidth(alphas.length > 0 ? Math.min(...alphas) : 1),
          n: p.samples ?? N_DEFAULT,
          seed: 8100 + index,
          stream: thetaO,
        });
        expectChi2Fit(r, ALPHA);
      });
    }
  });

  it('has power: a coat sampled at roughness 0.3 is rejected against the pdf of 0.36', () => {
    // Black base: at 70° the coat carries a third of the samples.
    const p: Params = {
      base: [0, 0, 0],
      metallic: 0,
      roughness: 1,
      clearcoat: 1,
      coatRoughness: 0.3,
    };
    const r = bsdfChi2({
      lobe: LAYERED,
      sp: setParams(p, new ShadingParams()),
      pdfSp: setParams({ ...p, coatRoughness: 0.36 }, new ShadingParams()),
      wo: direction(70),
      width: 0.2,
      n: N_DEFAULT,
      seed: 98,
    });
    expect(r.pValue).toBeLessThan(1e-6);
  });
});

describe('layered glTF BSDF: reciprocity', () => {
  it('f(wo, wi) = f(wi, wo) for every case, on random pairs', () => {
    const a = new BsdfValue();
    const b = new BsdfValue();
    let worst = 0;
    CASES.forEach(([, p], index) => {
      const sp = setParams(p);
      for (let i = 0; i < 2000; i++) {
        const key = sampleKey(4200 + index, i, 0);
        const wo = direction(Math.acos(hashToUnit(key, 0)) / DEG, 2 * Math.PI * hashToUnit(key, 1));
        const wi = direction(Math.acos(hashToUnit(key, 2)) / DEG, 2 * Math.PI * hashToUnit(key, 3));
        const e = evalBothWays(LAYERED, sp, wo, wi, a, b);
        expect(Number.isFinite(a.r + a.g + a.b)).toBe(true);
        worst = Math.max(worst, e);
      }
    });
    expect(worst).toBeLessThan(1e-12);
  });
});

const FURNACE_THETAS = [0, 30, 60, 80, 89];

function expectFurnace(cases: Params[], seed: number): void {
  const bad: string[] = [];
  cases.forEach((p, k) => {
    for (const theta of FURNACE_THETAS) {
      const {
        mean,
        se,
        bad: nonFinite,
      } = furnace(LAYERED, setParams(p), direction(theta), 8_000, seed + k, theta);
      if (nonFinite > 0) bad.push(`${JSON.stringify(p)} at ${theta}°: ${nonFinite} bad weights`);
      for (let c = 0; c < 3; c++) {
        if (mean[c] - 1 > 4 * se[c])
          bad.push(`${JSON.stringify(p)} at ${theta}°, channel ${c}: ${mean[c]} ± ${se[c]}`);
      }
    }
  });
  expect(bad).toEqual([]);
}

describe('layered glTF BSDF: white furnace (energy ≤ 1)', () => {
  for (const metallic of [0, 1]) {
    it(`clearcoat over a white base, metallic ${metallic}`, () => {
      const cases: Params[] = [];
      for (const roughness of [0, 0.3, 1])
        for (const clearcoat of [0.5, 1])
          for (const coatRoughness of [0, 0.3, 0.7, 1])
            cases.push({ base: [1, 1, 1], metallic, roughness, clearcoat, coatRoughness });
      expectFurnace(cases, 1300 + metallic * 100);
    });
  }
  for (const metallic of [0, 1]) {
    it(`sheen over a white base, metallic ${metallic}`, () => {
      const cases: Params[] = [];
      for (const sheen of [
        [0.5, 0.5, 0.5],
        [1, 1, 1],
        [1, 0.5, 0],
      ] as [number, number, number][])
        for (const sheenRoughness of [0.05, 0.3, 0.6, 1])
          cases.push({ base: [1, 1, 1], metallic, roughness: 0.3, sheen, sheenRoughness });
      expectFurnace(cases, 1600 + metallic * 100);
    });
  }
  it('clearcoat over sheen over a white base', () => {
    const cases: Params[] = [
      // …and over white glass, from outside (the refraction carries the rest).
      {
        base: [1, 1, 1],
        metallic: 0,
        roughness: 0.3,
        transmission: 1,
        clearcoat: 1,
        coatRoughness: 0.3,
      },
      {
        base: [1, 1, 1],
        metallic: 0,
        roughness: 0,
        transmission: 1,
        sheen: [1, 1, 1],
        sheenRoughness: 0.5,
      },
    ];
    for (const coatRoughness of [0, 0.5])
      for (const sheenRoughness of [0.05, 0.5])
        cases.push({
          base: [1, 1, 1],
          metallic: 0,
          roughness: 0.5,
          clearcoat: 1,
          coatRoughness,
          sheen: [1, 1, 1],
          sheenRoughness,
        });
    expectFurnace(cases, 1900);
  });
});

describe('layered glTF BSDF: reductions', () => {
  it('clearcoat 0 and black sheen are the base, bit for bit', () => {
    const a = new BsdfValue();
    const b = new BsdfValue();
    const sa = new BsdfSample();
    const sb = new BsdfSample();
    let differ = 0;
    for (const metallic of [0, 0.5, 1]) {
      for (const roughness of [0, 0.4]) {
        // The layers' other parameters set: only the weights make them vanish.
        const sp = setParams({
          metallic,
          roughness,
          clearcoat: 0,
          coatRoughness: 0.5,
          coatNormal: [0.2, 0.1, 1],
          sheen: [0, 0, 0],
          sheenRoughness: 0.5,
        });
        for (let i = 0; i < 500; i++) {
          const key = sampleKey(77, i, metallic * 10 + roughness * 100);
          const [ox, oy, oz] = direction(89 * hashToUnit(key, 0), 6 * hashToUnit(key, 1));
          const [ix, iy, iz] = direction(89 * hashToUnit(key, 2), 6 * hashToUnit(key, 3));
          Object.assign(q, { wox: ox, woy: oy, woz: oz, wix: ix, wiy: iy, wiz: iz });
          q.u0 = hashToUnit(key, 4);
          q.u1 = hashToUnit(key, 5);
          q.u2 = hashToUnit(key, 6);
          layeredEval(sp, q, a);
          gltfEval(sp, q, b);
          if (a.r !== b.r || a.g !== b.g || a.b !== b.b || a.pdf !== b.pdf) differ++;
          if (layeredPdf(sp, q) !== gltfPdf(sp, q)) differ++;
          const oa = layeredSample(sp, q, sa);
          const ob = gltfSample(sp, q, sb);
          if (oa !== ob || (oa && JSON.stringify(sa) !== JSON.stringify(sb))) differ++;
        }
      }
    }
    expect(differ).toBe(0);
  });

  it('unlit scatters nothing', () => {
    const sp = setParams({ metallic: 0, roughness: 0.5, clearcoat: 1, sheen: [1, 1, 1] });
    sp.unlit = true;
    const v = new BsdfValue();
    Object.assign(q, {
      wox: 0,
      woy: 0,
      woz: 1,
      wix: 0.6,
      wiy: 0,
      wiz: 0.8,
      u0: 0.3,
      u1: 0.3,
      u2: 0.9,
    });
    layeredEval(sp, q, v);
    expect([v.r, v.g, v.b, v.pdf]).toEqual([0, 0, 0, 0]);
    expect(layeredSample(sp, q, new BsdfSample())).toBe(false);
  });
});
