/**
 * Statistical tests of the transmission lobes issue 25 adds to the glTF BSDF
 * (src/core/bsdf/gltf-pbr.ts, diffuse-transmission.ts), modelled on
 * gltf-bsdf-chi2.test.ts:
 *
 * - χ² of `sample` against `pdf` on the whole sphere (two hemisphere grids: wo's
 *   side, concentrated around the mirror direction, and the far side), for the thin
 *   wall (KHR_materials_volume absent: η the same from both sides) and for
 *   KHR_materials_diffuse_transmission, wo from either side. Delta samples
 *   (mirror, straight-through refraction) and refusals share one pseudo-cell
 *   expected at N·(1 − ∫pdf). All cases together reject at 1% (Šidák).
 * - Reciprocity of f (both sides) to 1e-12.
 * - White furnace: the mean sample weight is at most 1 (four standard errors:
 *   false alarm < 1e-4 per case) over a grid of (transmission, diffuse
 *   transmission, roughness, metallic) and wo on both sides.
 * - Reductions: diffuse transmission 0 is the base whatever its colour; diffuse
 *   transmission 1 without a specular layer is the Lambertian BTDF colour/π; the
 *   thin wall seen from outside is the solid, sample for sample, except that its
 *   refraction goes straight on with weight baseColor·(1 − Fd), no (n1/n2)².
 */
import { describe, expect, it } from 'vitest';
import { gltfEval, gltfSample } from '../../src/core/bsdf/gltf-pbr.ts';
import { BsdfQuery, BsdfSample, BsdfValue } from '../../src/core/bsdf/records.ts';
import type { ShadingParams } from '../../src/core/bsdf/shading.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import {
  bsdfChi2,
  direction,
  evalBothWays,
  expectChi2Fit,
  furnace,
  gltfLobe,
  lobeWidth,
  relErr,
  setSampleQuery,
} from '../helpers/bsdf-chi2.ts';

interface Params {
  metallic?: number;
  roughness: number;
  transmission?: number;
  thickness?: number;
  dt?: number;
  dtColor?: [number, number, number];
  base?: [number, number, number];
  specular?: number;
}

const q = new BsdfQuery();

function setParams(p: Params): ShadingParams {
  const sp = q.shading;
  sp.reset();
  [sp.baseR, sp.baseG, sp.baseB] = p.base ?? [0.9, 0.6, 0.3];
  sp.metallic = p.metallic ?? 0;
  sp.alpha = p.roughness * p.roughness;
  sp.transmission = p.transmission ?? 0;
  sp.thickness = p.thickness ?? 0;
  sp.diffuseTransmission = p.dt ?? 0;
  [sp.dtR, sp.dtG, sp.dtB] = p.dtColor ?? [0.3, 0.8, 0.5];
  sp.specular = p.specular ?? 1;
  sp.ior = 1.5;
  return sp;
}

interface Case {
  name: string;
  params: Params;
  thetaO: number;
  inside: boolean;
}

const CASES: Case[] = [];
// The thin wall: only wo from behind differs from the solid (gltf-bsdf-chi2 tests outside).
for (const [metallic, transmission] of [
  [0, 1],
  [0.3, 0.6],
]) {
  for (const roughness of [0.1, 0.5]) {
    for (const thetaO of [0, 50, 85]) {
      CASES.push({
        name: `thin wall: metallic ${metallic}, transmission ${transmission}, roughness ${roughness}, wo at ${thetaO}° behind`,
        params: { metallic, transmission, roughness },
        thetaO,
        inside: true,
      });
    }
  }
}
for (const dt of [0.5, 1]) {
  for (const [roughness, transmission] of [
    [0, 0],
    [0.4, 0.5],
  ]) {
    for (const inside of [false, true]) {
      for (const thetaO of [0, 60, 85]) {
        CASES.push({
          name: `diffuse transmission ${dt}, roughness ${roughness}, transmission ${transmission}, wo at ${thetaO}°${inside ? ' behind' : ''}`,
          params: { dt, roughness, transmission },
          thetaO,
          inside,
        });
      }
    }
  }
}
const ALPHA = 1 - Math.pow(1 - 0.01, 1 / CASES.length);
/** Samples per case: the thin wall's non-delta part (rough reflection) holds only ~5%. */
const samplesOf = (c: Case): number => (c.params.dt ? 40_000 : 100_000);

describe('glTF transmission lobes: χ² of sample against pdf on the sphere', () => {
  CASES.forEach((c, index) => {
    it(c.name, () => {
      // Near: wo's side, around the mirror direction; far: the other side.
      const r = bsdfChi2({
        lobe: gltfLobe,
        sp: setParams(c.params),
        wo: direction(c.thetaO),
        inside: c.inside,
        width: lobeWidth(c.params.roughness ** 2),
        n: samplesOf(c),
        seed: 8100 + index,
        sphere: true,
      });
      expectChi2Fit(r, ALPHA);
    });
  });
});

describe('glTF transmission lobes: reciprocity', () => {
  it('f(wo, wi) = f(wi, wo) on both sides, thin wall and diffuse transmission (1e-12)', () => {
    const f = new BsdfValue();
    const g = new BsdfValue();
    let worst = 0;
    let far = 0;
    let n = 0;
    for (const dt of [0, 0.4, 1]) {
      for (const transmission of [0, 0.5]) {
        for (const roughness of [0, 0.3, 1]) {
          const sp = setParams({ dt, transmission, roughness, metallic: 0.2 });
          for (let i = 0; i < 300; i++) {
            const key = sampleKey(77 + n++, i, 0);
            const za = 2 * hashToUnit(key, 0) - 1;
            const zb = 2 * hashToUnit(key, 1) - 1;
            const pa = 2 * Math.PI * hashToUnit(key, 2);
            const pb = 2 * Math.PI * hashToUnit(key, 3);
            const ra = Math.sqrt(1 - za * za);
            const rb = Math.sqrt(1 - zb * zb);
            const a: [number, number, number] = [ra * Math.cos(pa), ra * Math.sin(pa), za];
            const b: [number, number, number] = [rb * Math.cos(pb), rb * Math.sin(pb), zb];
            worst = Math.max(worst, evalBothWays(gltfLobe, sp, a, b, f, g));
            if (za * zb < 0 && f.r > 0) far++;
          }
        }
      }
    }
    expect(worst).toBeLessThan(1e-12);
    // The far side was exercised (only diffuse transmission reaches it).
    expect(far).toBeGreaterThan(500);
  });
});

describe('glTF transmission lobes: white furnace (energy ≤ 1)', () => {
  const n = 8_000;
  for (const [dt, transmission] of [
    [1, 0],
    [0.5, 0],
    [0.5, 0.5],
    [0, 1],
  ]) {
    it(`thin wall, diffuse transmission ${dt}, transmission ${transmission}: every roughness, metallic and wo`, () => {
      let where = '';
      let bad = 0;
      for (const roughness of [0, 0.3, 1]) {
        for (const metallic of [0, 0.5]) {
          const sp = setParams({
            dt,
            transmission,
            roughness,
            metallic,
            base: [1, 1, 1],
            dtColor: [1, 1, 1],
          });
          for (const thetaO of [0, 60, 89]) {
            for (const inside of [false, true]) {
              const [x, y, z] = direction(thetaO);
              const stream = roughness * 100 + metallic * 10 + (inside ? 1 : 0);
              const e = furnace(gltfLobe, sp, [x, y, inside ? -z : z], n, 950 + thetaO, stream);
              bad += e.bad + e.notGrey;
              const [mean] = e.mean;
              const [se] = e.se;
              if (mean - 1 > 4 * se + 1e-12)
                where = `roughness ${roughness}, metallic ${metallic}, wo at ${thetaO}°${inside ? ' behind' : ''}: ${mean} ± ${se}`;
            }
          }
        }
      }
      expect(where).toBe('');
      expect(bad).toBe(0);
    });
  }
});

describe('glTF transmission lobes: reductions', () => {
  const a = new BsdfSample();
  const b = new BsdfSample();
  const fa = new BsdfValue();
  const fb = new BsdfValue();

  function sampleAll(p: Params, key: number, out: BsdfSample, fv: BsdfValue, i: number): boolean {
    const sp = setParams(p);
    const [x, y, z] = direction((i * 7) % 90);
    const inside = i % 2 === 1;
    setSampleQuery(q, x, y, inside ? -z : z, sampleKey(key, i, 0));
    const ok = gltfSample(sp, q, out);
    q.wix = -y;
    q.wiy = x;
    q.wiz = (i % 3) - 1 || 0.5;
    gltfEval(sp, q, fv);
    return ok;
  }

  it('diffuse transmission 0 is the base material whatever its colour, bit for bit', () => {
    let differ = 0;
    for (const roughness of [0, 0.4]) {
      for (const transmission of [0, 0.5]) {
        for (let i = 0; i < 500; i++) {
          const p: Params = { roughness, transmission, metallic: 0.3, dt: 0 };
          const oa = sampleAll({ ...p, dtColor: [1, 1, 1] }, 5, a, fa, i);
          const ob = sampleAll({ ...p, dtColor: [0.1, 0.9, 0.2] }, 5, b, fb, i);
          if (
            oa !== ob ||
            (oa && (a.wx !== b.wx || a.wz !== b.wz || a.weightR !== b.weightR || a.pdf !== b.pdf))
          )
            differ++;
          if (fa.r !== fb.r || fa.g !== fb.g || fa.pdf !== fb.pdf) differ++;
        }
      }
    }
    expect(differ).toBe(0);
  });

  it('diffuse transmission 1 without a specular layer is the Lambertian BTDF colour/π', () => {
    const color: [number, number, number] = [0.3, 0.8, 0.5];
    const sp = setParams({ roughness: 0.5, dt: 1, dtColor: color, specular: 0 });
    const f = new BsdfValue();
    for (const [oz, iz] of [
      [0.9, -0.3],
      [-0.2, 0.7],
    ]) {
      q.wox = Math.sqrt(1 - oz * oz);
      q.woy = 0;
      q.woz = oz;
      q.wix = 0;
      q.wiy = Math.sqrt(1 - iz * iz);
      q.wiz = iz;
      gltfEval(sp, q, f);
      expect(f.r).toBeCloseTo(color[0] / Math.PI, 14);
      expect(f.g).toBeCloseTo(color[1] / Math.PI, 14);
      expect(f.b).toBeCloseTo(color[2] / Math.PI, 14);
      expect(f.pdf).toBeCloseTo(Math.abs(iz) / Math.PI, 14);
      // …and nothing is reflected.
      q.wiz = -iz;
      gltfEval(sp, q, f);
      expect(f.r).toBe(0);
    }
  });

  it('the thin wall seen from outside is the solid, except that refraction goes straight on', () => {
    let differ = 0;
    let refractions = 0;
    for (const roughness of [0, 0.3]) {
      for (let i = 0; i < 600; i++) {
        const p: Params = { roughness, transmission: 1, base: [0.9, 0.6, 0.3] };
        const [x, y, z] = direction((i * 7) % 90);
        for (const [thickness, out] of [
          [0, a],
          [1, b],
        ] as const) {
          const sp = setParams({ ...p, thickness });
          setSampleQuery(q, x, y, z, sampleKey(6, i, roughness * 10));
          // A refusal leaves the record as it was: mark it.
          if (!gltfSample(sp, q, out)) out.pdf = -1;
        }
        if (a.pdf !== b.pdf || a.isDelta !== b.isDelta) differ++;
        else if (a.pdf === -1)
          continue; // both refused
        else if (a.wz < 0) {
          refractions++;
          // Straight through, and no (n1/n2)²: the solid's weight times η².
          if (a.wx !== -x || a.wy !== -y || a.wz !== -z || a.etaScale !== 1) differ++;
          if (relErr(a.weightR, b.weightR * b.etaScale) > 1e-14) differ++;
        } else if (a.wx !== b.wx || a.wz !== b.wz || a.weightR !== b.weightR) differ++;
      }
    }
    expect(differ).toBe(0);
    expect(refractions).toBeGreaterThan(600);
  });
});
