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
import { gltfEval, gltfPdf, gltfSample } from '../../src/core/bsdf/gltf-pbr.ts';
import { BsdfQuery, BsdfSample, BsdfValue } from '../../src/core/bsdf/records.ts';
import type { ShadingParams } from '../../src/core/bsdf/shading.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import { chi2Test } from '../helpers/chi2.ts';
import { HemisphereGrid } from '../helpers/hemisphere-grid.ts';

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

const DEG = Math.PI / 180;
const PHI_O = 0.7;

function direction(thetaDeg: number): [number, number, number] {
  const t = thetaDeg * DEG;
  return [Math.sin(t) * Math.cos(PHI_O), Math.sin(t) * Math.sin(PHI_O), Math.cos(t)];
}

function relErr(a: number, b: number): number {
  const m = Math.max(Math.abs(a), Math.abs(b));
  return m === 0 ? 0 : Math.abs(a - b) / m;
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
      const N = samplesOf(c);
      const sp = setParams(c.params);
      const s = c.inside ? -1 : 1;
      const [wox, woy, oz] = direction(c.thetaO);
      const woz = s * oz;
      // Near: wo's side (z mirrored from behind); far: the other side, z mirrored again.
      const pdfAt = (x: number, y: number, z: number): number => {
        q.wox = wox;
        q.woy = woy;
        q.woz = woz;
        q.wix = x;
        q.wiy = y;
        q.wiz = z;
        return gltfPdf(sp, q);
      };
      const alpha = c.params.roughness ** 2;
      const width = alpha === 0 ? 10 : Math.max(2.5 * alpha, 1e-3);
      const near = HemisphereGrid.around(oz < 1 ? Math.acos(oz) : 0, Math.atan2(-woy, -wox), width);
      const far = HemisphereGrid.around(0, 0, 10, 12, 24);
      const en = near.integrate((x, y, z) => pdfAt(x, y, s * z));
      const ef = far.integrate((x, y, z) => pdfAt(x, y, -s * z));
      const cells = near.below + far.below + 1;
      const failed = cells - 1;
      const expected = new Float64Array(cells);
      let mass = 0;
      for (let i = 0; i < near.below; i++) {
        expected[i] = en[i] * N;
        mass += en[i];
      }
      for (let i = 0; i < far.below; i++) {
        expected[near.below + i] = ef[i] * N;
        mass += ef[i];
      }
      expected[failed] = N * Math.max(0, 1 - mass);
      const observed = new Float64Array(cells);
      const out = new BsdfSample();
      const f = new BsdfValue();
      let weightErr = 0;
      let pdfErr = 0;
      for (let i = 0; i < N; i++) {
        const key = sampleKey(8100 + index, i, 0);
        q.wox = wox;
        q.woy = woy;
        q.woz = woz;
        q.u0 = hashToUnit(key, 0);
        q.u1 = hashToUnit(key, 1);
        q.u2 = hashToUnit(key, 2);
        if (!gltfSample(sp, q, out) || out.isDelta) {
          observed[failed]++;
          continue;
        }
        const z = s * out.wz;
        observed[
          z > 0 ? near.cellOf(out.wx, out.wy, z) : near.below + far.cellOf(out.wx, out.wy, -z)
        ]++;
        q.wix = out.wx;
        q.wiy = out.wy;
        q.wiz = out.wz;
        gltfEval(sp, q, f);
        pdfErr = Math.max(pdfErr, relErr(out.pdf, f.pdf), relErr(f.pdf, gltfPdf(sp, q)));
        const k = Math.abs(out.wz) / out.pdf;
        weightErr = Math.max(
          weightErr,
          relErr(out.weightR, f.r * k),
          relErr(out.weightG, f.g * k),
          relErr(out.weightB, f.b * k),
        );
      }
      const r = chi2Test(observed, expected);
      expect(r.impossible).toBeNull();
      expect(mass).toBeLessThan(1 + 1e-6);
      expect(r.dof).toBeGreaterThan(50);
      expect(
        r.pValue,
        `χ² = ${r.stat.toFixed(1)} on ${r.dof} dof; rest ${observed[failed]} vs ${expected[failed].toFixed(1)}`,
      ).toBeGreaterThan(ALPHA);
      expect(weightErr).toBeLessThan(1e-9);
      expect(pdfErr).toBeLessThan(1e-9);
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
          setParams({ dt, transmission, roughness, metallic: 0.2 });
          for (let i = 0; i < 300; i++) {
            const key = sampleKey(77 + n++, i, 0);
            const za = 2 * hashToUnit(key, 0) - 1;
            const zb = 2 * hashToUnit(key, 1) - 1;
            const pa = 2 * Math.PI * hashToUnit(key, 2);
            const pb = 2 * Math.PI * hashToUnit(key, 3);
            const ra = Math.sqrt(1 - za * za);
            const rb = Math.sqrt(1 - zb * zb);
            const a = [ra * Math.cos(pa), ra * Math.sin(pa), za];
            const b = [rb * Math.cos(pb), rb * Math.sin(pb), zb];
            [q.wox, q.woy, q.woz, q.wix, q.wiy, q.wiz] = [...a, ...b];
            gltfEval(q.shading, q, f);
            [q.wox, q.woy, q.woz, q.wix, q.wiy, q.wiz] = [...b, ...a];
            gltfEval(q.shading, q, g);
            worst = Math.max(worst, relErr(f.r, g.r), relErr(f.g, g.g), relErr(f.b, g.b));
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
              const out = new BsdfSample();
              let sum = 0;
              let sum2 = 0;
              for (let i = 0; i < n; i++) {
                const key = sampleKey(
                  950 + thetaO,
                  i,
                  roughness * 100 + metallic * 10 + (inside ? 1 : 0),
                );
                q.wox = x;
                q.woy = y;
                q.woz = inside ? -z : z;
                q.u0 = hashToUnit(key, 0);
                q.u1 = hashToUnit(key, 1);
                q.u2 = hashToUnit(key, 2);
                let e = 0;
                if (gltfSample(sp, q, out)) {
                  e = out.weightR * out.etaScale;
                  if (!(Number.isFinite(e) && e >= 0) || out.weightG !== out.weightR) bad++;
                }
                sum += e;
                sum2 += e * e;
              }
              const mean = sum / n;
              const se = Math.sqrt(Math.max(0, sum2 / n - mean * mean) / n);
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
    q.wox = x;
    q.woy = y;
    q.woz = inside ? -z : z;
    const k = sampleKey(key, i, 0);
    q.u0 = hashToUnit(k, 0);
    q.u1 = hashToUnit(k, 1);
    q.u2 = hashToUnit(k, 2);
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
          q.wox = x;
          q.woy = y;
          q.woz = z;
          const k = sampleKey(6, i, roughness * 10);
          q.u0 = hashToUnit(k, 0);
          q.u1 = hashToUnit(k, 1);
          q.u2 = hashToUnit(k, 2);
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
