/**
 * The glTF metallic–roughness BSDF through the core's one switch
 * (bsdf.ts, material kind MATERIAL_GLTF): reciprocity, eval/pdf agreement,
 * and the reductions that must hold exactly at the BSDF level —
 * - metallic 1 is the scene format's conductor with F0 = baseColor;
 * - no specular layer (KHR_materials_specular factor 0) is the diffuse material;
 * - transmission 1 with roughness 0 is the smooth dielectric.
 * (Render-level block tests of the same reductions come with the integrator.)
 */
import { describe, expect, it } from 'vitest';
import {
  compileMaterials,
  MATERIAL_GLTF,
  MATERIAL_STRIDE,
  M_TYPE,
} from '../../../src/core/bsdf/materials.ts';
import { usesGeometricSide } from '../../../src/core/bsdf/bsdf.ts';
import { BsdfSample, BsdfValue } from '../../../src/core/bsdf/records.ts';
import type { ShadingParams } from '../../../src/core/bsdf/shading.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import type { Vec3 } from '../../../src/core/scene/format/types.ts';
import { bsdfEval, bsdfPdf, bsdfSample, shading } from '../../helpers/bsdf-calls.ts';

const BLACK: Vec3 = [0, 0, 0];
const COLOR: Vec3 = [0.9, 0.6, 0.3];
const ROUGHNESSES = [0, 0.05, 0.3, 0.7, 1];

/** Reference materials from the scene format, and one glTF material at the end. */
const REF = compileMaterials([
  ...ROUGHNESSES.map((roughness) => ({
    type: 'conductor' as const,
    color: COLOR,
    roughness,
    emission: BLACK,
  })),
  { type: 'diffuse', albedo: COLOR, emission: BLACK },
  { type: 'dielectric', ior: 1.5, color: COLOR, roughness: 0, emission: BLACK },
  { type: 'dielectric', ior: 1.33, color: [1, 1, 1], roughness: 0, emission: BLACK },
]);
const DIFFUSE = ROUGHNESSES.length;
const GLASS = DIFFUSE + 1;
const WATER = DIFFUSE + 2;
const GLTF = WATER + 1;
const MATERIALS = new Float64Array(REF.length + MATERIAL_STRIDE);
MATERIALS.set(REF);
MATERIALS[GLTF * MATERIAL_STRIDE + M_TYPE] = MATERIAL_GLTF;

function setGltf(p: Partial<ShadingParams> & { roughness?: number }): ShadingParams {
  const sp = shading();
  sp.reset();
  const { roughness, ...rest } = p;
  Object.assign(sp, rest);
  if (roughness !== undefined) sp.alpha = roughness === 0 ? 0 : Math.max(1e-6, roughness ** 2);
  return sp;
}

function rand(seed: number, i: number, d: number): number {
  return hashToUnit(sampleKey(seed, i, 0), d);
}

/** Uniform direction on the sphere (z of either sign), or the upper hemisphere. */
function randomDir(seed: number, i: number, upper = false): [number, number, number] {
  const z = upper ? rand(seed, i, 0) : 2 * rand(seed, i, 0) - 1;
  const r = Math.sqrt(Math.max(0, 1 - z * z));
  const p = 2 * Math.PI * rand(seed, i, 1);
  return [r * Math.cos(p), r * Math.sin(p), z];
}

function relErr(a: number, b: number): number {
  const m = Math.max(Math.abs(a), Math.abs(b));
  return m === 0 ? 0 : Math.abs(a - b) / m;
}

describe('glTF BSDF: eval', () => {
  const f = new BsdfValue();
  const g = new BsdfValue();

  it('is reciprocal, finite and non-negative over a grid of parameters (1e-12)', () => {
    let worst = 0;
    let positive = 0;
    let bad = 0;
    let n = 0;
    for (const metallic of [0, 0.4, 1]) {
      for (const transmission of [0, 0.5, 1]) {
        for (const roughness of ROUGHNESSES) {
          for (const [specular, thickness] of [
            [1, 0],
            [0.3, 0],
            [1, 1],
          ]) {
            // thickness 0: the thin wall; 1: a volume (KHR_materials_volume).
            setGltf({
              baseR: 0.8,
              baseG: 0.5,
              baseB: 0.1,
              metallic,
              transmission,
              roughness,
              specular,
              ior: 1.4,
              thickness,
            });
            for (let i = 0; i < 400; i++) {
              const [ax, ay, az] = randomDir(10 + n, i);
              // wi on the same side as wo (reflection), or anywhere.
              const [bx, by, bzRaw] = randomDir(20 + n, i);
              const bz = i % 2 === 0 ? Math.sign(az) * Math.abs(bzRaw) : bzRaw;
              bsdfEval(MATERIALS, GLTF, ax, ay, az, bx, by, bz, f);
              bsdfEval(MATERIALS, GLTF, bx, by, bz, ax, ay, az, g);
              worst = Math.max(worst, relErr(f.r, g.r), relErr(f.g, g.g), relErr(f.b, g.b));
              if (f.r > 0) positive++;
              for (const v of [f.r, f.g, f.b, f.pdf]) if (!(Number.isFinite(v) && v >= 0)) bad++;
              if (f.pdf !== bsdfPdf(MATERIALS, GLTF, ax, ay, az, bx, by, bz)) bad++;
              // Opposite sides: only the (delta) refraction connects them.
              if (az * bz < 0 && (f.r !== 0 || f.pdf !== 0)) bad++;
            }
            n++;
          }
        }
      }
    }
    expect(bad).toBe(0);
    expect(worst).toBeLessThan(1e-12);
    expect(positive).toBeGreaterThan(n * 100);
  });

  it('a transmissive glTF material needs the geometric side only when the record says so', () => {
    expect(usesGeometricSide(MATERIALS, GLASS)).toBe(true);
    expect(usesGeometricSide(MATERIALS, DIFFUSE)).toBe(false);
    expect(usesGeometricSide(MATERIALS, GLTF)).toBe(false);
  });
});

describe('glTF BSDF: reductions', () => {
  const f = new BsdfValue();
  const g = new BsdfValue();
  const s = new BsdfSample();
  const t = new BsdfSample();

  function compareSamples(ref: number, seed: number, inside = false): number {
    let worst = 0;
    let sampled = 0;
    for (let i = 0; i < 5000; i++) {
      const [x, y, zUp] = randomDir(seed, i, true);
      const z = inside ? -zUp : zUp;
      const u0 = rand(seed + 1, i, 0);
      const u1 = rand(seed + 1, i, 1);
      const u2 = rand(seed + 1, i, 2);
      const a = bsdfSample(MATERIALS, ref, x, y, z, u0, u1, u2, s);
      const b = bsdfSample(MATERIALS, GLTF, x, y, z, u0, u1, u2, t);
      if (a !== b) return Infinity;
      if (!a) continue;
      sampled++;
      if (s.isDelta !== t.isDelta || s.etaScale !== t.etaScale) return Infinity;
      worst = Math.max(
        worst,
        Math.abs(s.wx - t.wx),
        Math.abs(s.wy - t.wy),
        Math.abs(s.wz - t.wz),
        relErr(s.weightR, t.weightR),
        relErr(s.weightG, t.weightG),
        relErr(s.weightB, t.weightB),
        relErr(s.pdf, t.pdf),
      );
    }
    expect(sampled).toBeGreaterThan(2000);
    return worst;
  }

  function compareEval(ref: number, seed: number): number {
    let worst = 0;
    for (let i = 0; i < 5000; i++) {
      const [ax, ay, az] = randomDir(seed, i, true);
      const [bx, by, bz] = randomDir(seed + 1, i, true);
      bsdfEval(MATERIALS, ref, ax, ay, az, bx, by, bz, f);
      bsdfEval(MATERIALS, GLTF, ax, ay, az, bx, by, bz, g);
      worst = Math.max(
        worst,
        relErr(f.r, g.r),
        relErr(f.g, g.g),
        relErr(f.b, g.b),
        relErr(f.pdf, g.pdf),
        relErr(
          bsdfPdf(MATERIALS, ref, ax, ay, az, bx, by, bz),
          bsdfPdf(MATERIALS, GLTF, ax, ay, az, bx, by, bz),
        ),
      );
    }
    return worst;
  }

  ROUGHNESSES.forEach((roughness, k) => {
    it(`metallic 1 is the conductor with F0 = baseColor (roughness ${roughness})`, () => {
      // Whatever the dielectric parameters: metallic 1 leaves none of them.
      setGltf({
        baseR: COLOR[0],
        baseG: COLOR[1],
        baseB: COLOR[2],
        metallic: 1,
        roughness,
        ior: 1.7,
        specular: 0.5,
      });
      expect(compareEval(k, 100 + k)).toBeLessThan(1e-12);
      expect(compareSamples(k, 200 + k)).toBeLessThan(1e-12);
    });
  });

  it.each([0, 0.3, 1])(
    'specular 0 (no layer) is the diffuse material with albedo baseColor (roughness %s)',
    (roughness) => {
      setGltf({ baseR: COLOR[0], baseG: COLOR[1], baseB: COLOR[2], specular: 0, roughness });
      expect(compareEval(DIFFUSE, 300)).toBeLessThan(1e-12);
      expect(compareSamples(DIFFUSE, 400)).toBeLessThan(1e-12);
    },
  );

  it('transmission 1 with roughness 0 on a volume is the smooth dielectric (outside and inside)', () => {
    setGltf({
      baseR: COLOR[0],
      baseG: COLOR[1],
      baseB: COLOR[2],
      transmission: 1,
      roughness: 0,
      ior: 1.5,
      thickness: 1,
    });
    expect(compareSamples(GLASS, 500)).toBeLessThan(1e-12);
    expect(compareSamples(GLASS, 600, true)).toBeLessThan(1e-12);
    setGltf({ transmission: 1, roughness: 0, ior: 1.33, thickness: 1 });
    expect(compareSamples(WATER, 700)).toBeLessThan(1e-12);
    expect(compareSamples(WATER, 800, true)).toBeLessThan(1e-12);
    // Both are pure Dirac: eval and pdf vanish.
    expect(compareEval(GLASS, 900)).toBe(0);
  });
});
