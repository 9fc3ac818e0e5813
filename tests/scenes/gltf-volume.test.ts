/**
 * KHR_materials_volume, KHR_materials_dispersion and thin-walled transmission in
 * whole renders (issue 25; docs/gltf.md "Transmission, volume, dispersion and
 * diffuse transmission"):
 *
 * - Beer–Lambert, analytic: a slab of thickness d seen head-on (fov 1°, so every
 *   camera ray is within 0.71° of the normal: path lengths within 1e-4 of d) in a
 *   constant white environment. At index 1 the render is exp(−σa·d) exactly; at
 *   index n it is the slab's transmission plus its reflection with all internal
 *   bounces, (1−F)²T/(1−F²T²) + F + (1−F)²F·T²/(1−F²T²), T = exp(−σa·d),
 *   F = ((n−1)/(n+1))² (normal incidence). Compared with the image mean, |z| < 4.5
 *   (false alarm 7e-6 per channel).
 * - Dispersion: the same slab with the per-channel indices of the extension's RGB
 *   approximation, rendered with one channel per path (dispersion.ts): each channel
 *   matches the formula at its own index, which tests the 3·e_c estimator.
 * - The thin wall: a single quad at index 1.5 is F + (1 − F)·baseColor.
 * - Reductions, bit for bit (same seed, same film): an infinite attenuation distance
 *   (any colour) and a white attenuation colour (any distance) are the plain
 *   transmission of the volume; dispersion 0 is no dispersion.
 * - A lamp inside an absorbing rough-glass box: light sampling from inside the
 *   volume (shadow rays attenuated) agrees with BSDF sampling alone (block test of
 *   gltf-features.test.ts: Σz² below the χ² quantile at p = 0.001, |z| < 5); so does
 *   a diffusely transmitting leaf lit from behind (KHR_materials_diffuse_transmission),
 *   and its factor 0 is no extension, bit for bit.
 */
import { Document } from '@gltf-transform/core';
import {
  KHRMaterialsDiffuseTransmission,
  KHRMaterialsDispersion,
  KHRMaterialsIOR,
  KHRMaterialsTransmission,
  KHRMaterialsVolume,
} from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import type { Scene } from '../../src/core/index.ts';
import { dispersedIor } from '../../src/core/bsdf/dispersion.ts';
import { docWith, meshPrimitive, sceneWithFiles, toGlb } from '../helpers/gltf.ts';
import { cube } from '../helpers/mesh-gen.ts';
import {
  blockChiSquarePair,
  chiSquareQuantile,
  imageMean,
  renderSampled,
} from '../helpers/render.ts';

interface Glass {
  base?: [number, number, number];
  ior?: number;
  roughness?: number;
  /** KHR_materials_volume; absent: no extension (a thin wall). */
  volume?: { thickness: number; color?: [number, number, number]; distance?: number };
  dispersion?: number;
}

function glassMaterial(doc: Document, g: Glass) {
  const tr = doc.createExtension(KHRMaterialsTransmission).createTransmission();
  const m = doc
    .createMaterial()
    .setBaseColorFactor([...(g.base ?? [1, 1, 1]), 1] as [number, number, number, number])
    .setMetallicFactor(0)
    .setRoughnessFactor(g.roughness ?? 0)
    .setExtension('KHR_materials_transmission', tr.setTransmissionFactor(1))
    .setExtension(
      'KHR_materials_ior',
      doc
        .createExtension(KHRMaterialsIOR)
        .createIOR()
        .setIOR(g.ior ?? 1.5),
    );
  if (g.volume !== undefined) {
    const v = doc.createExtension(KHRMaterialsVolume).createVolume();
    v.setThicknessFactor(g.volume.thickness);
    if (g.volume.color) v.setAttenuationColor(g.volume.color);
    if (g.volume.distance !== undefined) v.setAttenuationDistance(g.volume.distance);
    m.setExtension('KHR_materials_volume', v);
  }
  if (g.dispersion !== undefined) {
    const d = doc.createExtension(KHRMaterialsDispersion).createDispersion();
    m.setExtension('KHR_materials_dispersion', d.setDispersion(g.dispersion));
  }
  return m;
}

const D = 0.5;

/** A closed box x, y ∈ [−5, 5], z ∈ [−d, 0], or (thin) the single quad z = 0. */
async function slabScene(g: Glass, thin = false): Promise<Scene> {
  const doc = new Document();
  const c = cube();
  const prim = thin
    ? meshPrimitive(doc, [-5, -5, 0, 5, -5, 0, 5, 5, 0, -5, 5, 0], [0, 1, 2, 0, 2, 3])
    : meshPrimitive(
        doc,
        Array.from(c.positions, (v, i) => (i % 3 === 2 ? (v - 1) * D : v * 10 - 5)),
        c.indices,
      );
  docWith(doc, prim.setMaterial(glassMaterial(doc, g)));
  const json = {
    format: 'pathwise-scene/1',
    camera: { position: [0, 0, 3], target: [0, 0, 0], up: [0, 1, 0], fovY: 1 },
    settings: { width: 8, height: 8, maxBounces: 24, spp: 64 },
    materials: {},
    shapes: [{ type: 'gltf', file: 's.glb' }],
    environment: [1, 1, 1],
  };
  return sceneWithFiles(json, new Map([['s.glb', await toGlb(doc)]]));
}

/** Transmission plus reflection of a slab with internal transmittance T, per interface F. */
function slab(T: number, F: number): number {
  const k = 1 - F * F * T * T;
  return ((1 - F) ** 2 * T) / k + F + ((1 - F) ** 2 * F * T * T) / k;
}

function fresnel0(n: number): number {
  return ((n - 1) / (n + 1)) ** 2;
}

const COLOR: [number, number, number] = [0.8, 0.5, 0.2];
const DISTANCE = 0.7;

function expectMean(scene: Scene, expected: number[], spp: number, seed: number): void {
  const img = renderSampled(scene, { spp, seed, sampler: 'independent' });
  expect(img.stats.rejected).toBe(0);
  const { mean, stderr } = imageMean(img);
  for (let c = 0; c < 3; c++) {
    const z = (mean[c] - expected[c]) / Math.max(stderr[c], 1e-12);
    expect(Math.abs(z), `channel ${c}: ${mean[c]} ± ${stderr[c]} vs ${expected[c]}`).toBeLessThan(
      4.5,
    );
  }
}

describe('KHR_materials_volume: Beer–Lambert absorption', () => {
  it('index 1: the slab transmits exp(−σa·d) exactly', async () => {
    const scene = await slabScene({
      ior: 1,
      volume: { thickness: D, color: COLOR, distance: DISTANCE },
    });
    const img = renderSampled(scene, { spp: 4, seed: 1, sampler: 'independent' });
    const { mean } = imageMean(img);
    for (let c = 0; c < 3; c++) {
      const sigma = -Math.log(COLOR[c]) / DISTANCE;
      expect(mean[c]).toBeCloseTo(Math.exp(-sigma * D), 4);
    }
  });

  it('index 1.5: transmission and reflection with every internal bounce', async () => {
    const scene = await slabScene({
      ior: 1.5,
      volume: { thickness: D, color: COLOR, distance: DISTANCE },
    });
    const F = fresnel0(1.5);
    const expected = COLOR.map((a) => slab(Math.exp((Math.log(a) / DISTANCE) * D), F));
    expectMean(scene, expected, 256, 2);
  });

  it('has power: the same render is rejected against a 5% longer path', async () => {
    const scene = await slabScene({
      ior: 1.5,
      volume: { thickness: D, color: COLOR, distance: DISTANCE },
    });
    const F = fresnel0(1.5);
    const img = renderSampled(scene, { spp: 256, seed: 2, sampler: 'independent' });
    const { mean, stderr } = imageMean(img);
    const wrong = slab(Math.exp((Math.log(COLOR[2]) / DISTANCE) * D * 1.05), F);
    expect(Math.abs(mean[2] - wrong) / stderr[2]).toBeGreaterThan(4.5);
  });

  it('reductions, bit for bit: infinite distance, or white colour, is plain transmission', async () => {
    const film = async (g: Glass) => {
      const img = renderSampled(await slabScene(g), { spp: 16, seed: 3 });
      return Array.from(img.mean);
    };
    const plain = await film({ ior: 1.5, volume: { thickness: D } });
    expect(await film({ ior: 1.5, volume: { thickness: D, color: COLOR } })).toEqual(plain);
    expect(
      await film({ ior: 1.5, volume: { thickness: D, color: [1, 1, 1], distance: 0.1 } }),
    ).toEqual(plain);
    // …and absorption does change it.
    expect(
      await film({ ior: 1.5, volume: { thickness: D, color: COLOR, distance: DISTANCE } }),
    ).not.toEqual(plain);
  });
});

describe('thin-walled transmission (no KHR_materials_volume, or thickness 0)', () => {
  it('a single pane is F + (1 − F)·baseColor: straight through, no bending', async () => {
    const base: [number, number, number] = [0.9, 0.6, 0.3];
    const F = fresnel0(1.5);
    expectMean(
      await slabScene({ ior: 1.5, base }, true),
      base.map((b) => F + (1 - F) * b),
      64,
      4,
    );
    // thicknessFactor 0 is the same thin wall, bit for bit.
    const a = renderSampled(await slabScene({ ior: 1.5, base }, true), { spp: 8, seed: 5 });
    const b = renderSampled(await slabScene({ ior: 1.5, base, volume: { thickness: 0 } }, true), {
      spp: 8,
      seed: 5,
    });
    expect(Array.from(a.mean)).toEqual(Array.from(b.mean));
  });
});

describe('KHR_materials_dispersion: one channel per path', () => {
  it('each channel of a dispersive slab matches the slab at its own index', async () => {
    const dispersion = 10;
    const scene = await slabScene({
      ior: 1.5,
      volume: { thickness: D, color: COLOR, distance: DISTANCE },
      dispersion,
    });
    const expected = COLOR.map((a, c) =>
      slab(Math.exp((Math.log(a) / DISTANCE) * D), fresnel0(dispersedIor(1.5, dispersion, c))),
    );
    // The spread of the indices is large enough for the test to see it.
    expect(
      Math.abs(expected[2] - slab(Math.exp((Math.log(COLOR[2]) / DISTANCE) * D), fresnel0(1.5))),
    ).toBeGreaterThan(0.005);
    expectMean(scene, expected, 512, 6);
  });

  it('dispersion 0 is no dispersion, bit for bit', async () => {
    const g: Glass = { ior: 1.5, volume: { thickness: D, color: COLOR, distance: DISTANCE } };
    const a = renderSampled(await slabScene(g), { spp: 16, seed: 7 });
    const b = renderSampled(await slabScene({ ...g, dispersion: 0 }), { spp: 16, seed: 7 });
    expect(Array.from(a.mean)).toEqual(Array.from(b.mean));
  });
});

describe('a lamp inside an absorbing volume', () => {
  it('light sampling from inside agrees with BSDF sampling alone', async () => {
    const doc = new Document();
    const c = cube();
    const box = meshPrimitive(
      doc,
      Array.from(c.positions, (v, i) => (i % 3 === 1 ? v * 0.8 + 0.2 : v * 1.2 - 0.6)),
      c.indices,
    );
    const mat = glassMaterial(doc, {
      base: [0.9, 0.8, 0.7],
      roughness: 0.4,
      volume: { thickness: 1, color: [0.3, 0.6, 0.9], distance: 0.5 },
    });
    docWith(doc, box.setMaterial(mat));
    const json = {
      format: 'pathwise-scene/1',
      camera: { position: [0, 2.2, 3], target: [0, 0.3, 0], up: [0, 1, 0], fovY: 45 },
      settings: { width: 16, height: 16, maxBounces: 4, spp: 64 },
      materials: {
        floor: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
        bright: { type: 'diffuse', albedo: [0, 0, 0], emission: [8, 8, 8] },
      },
      shapes: [
        { type: 'quad', corner: [-2, 0, 2], u: [4, 0, 0], v: [0, 0, -4], material: 'floor' },
        {
          type: 'quad',
          corner: [-0.3, 0.4, 0.3],
          u: [0.6, 0, 0],
          v: [0, 0, -0.6],
          material: 'bright',
        },
        { type: 'gltf', file: 'm.glb' },
      ],
      environment: [0.05, 0.05, 0.05],
    };
    const scene = await sceneWithFiles(json, new Map([['m.glb', await toGlb(doc)]]));
    const a = renderSampled(scene, {
      spp: 64,
      seed: 8,
      estimator: 'nee-mis',
      sampler: 'independent',
    });
    const b = renderSampled(scene, { spp: 64, seed: 9, estimator: 'bsdf', sampler: 'independent' });
    expect(a.stats.rejected + b.stats.rejected).toBe(0);
    const { chi2, dof, maxAbsZ } = blockChiSquarePair(a, b, 4);
    expect(dof).toBeGreaterThan(30);
    expect(chi2).toBeLessThan(chiSquareQuantile(dof, 3.09));
    expect(maxAbsZ).toBeLessThan(5);
  });
});

describe('KHR_materials_diffuse_transmission in the tracer', () => {
  /** A leaf-like quad (y = 1, facing up) under a lamp, seen from below. */
  async function leafScene(factor: number | null): Promise<Scene> {
    const doc = new Document();
    const m = doc
      .createMaterial()
      .setBaseColorFactor([0.6, 0.8, 0.4, 1])
      .setMetallicFactor(0)
      .setRoughnessFactor(0.6);
    if (factor !== null) {
      const dt = doc
        .createExtension(KHRMaterialsDiffuseTransmission)
        .createDiffuseTransmission()
        .setDiffuseTransmissionFactor(factor)
        .setDiffuseTransmissionColorFactor([0.9, 0.7, 0.2]);
      m.setExtension('KHR_materials_diffuse_transmission', dt);
    }
    const leaf = meshPrimitive(doc, [-1, 1, -1, -1, 1, 1, 1, 1, 1, 1, 1, -1], [0, 1, 2, 0, 2, 3]);
    docWith(doc, leaf.setMaterial(m));
    const json = {
      format: 'pathwise-scene/1',
      // Straight below: the lamp is hidden by the leaf (seen directly past its edge, its
      // bright pixels would only test the camera).
      camera: { position: [0, -1, 0], target: [0, 1, 0], up: [0, 0, 1], fovY: 60 },
      settings: { width: 24, height: 24, maxBounces: 3, spp: 64 },
      materials: {
        bright: { type: 'diffuse', albedo: [0, 0, 0], emission: [4, 4, 4] },
      },
      shapes: [
        // Facing down (u × v points to −y), over the leaf.
        { type: 'quad', corner: [-0.5, 2, -0.5], u: [1, 0, 0], v: [0, 0, 1], material: 'bright' },
        { type: 'gltf', file: 'leaf.glb' },
      ],
      environment: [0.02, 0.02, 0.02],
    };
    return sceneWithFiles(json, new Map([['leaf.glb', await toGlb(doc)]]));
  }

  it('light through a leaf: light sampling from behind agrees with BSDF sampling alone', async () => {
    const scene = await leafScene(0.8);
    const a = renderSampled(scene, {
      spp: 64,
      seed: 10,
      estimator: 'nee-mis',
      sampler: 'independent',
    });
    const b = renderSampled(scene, {
      spp: 64,
      seed: 11,
      estimator: 'bsdf',
      sampler: 'independent',
    });
    expect(a.stats.rejected + b.stats.rejected).toBe(0);
    // The underside is lit only through the leaf.
    expect(imageMean(a).mean[0]).toBeGreaterThan(0.05);
    const { chi2, dof, maxAbsZ } = blockChiSquarePair(a, b, 4);
    expect(dof).toBeGreaterThan(30);
    expect(chi2).toBeLessThan(chiSquareQuantile(dof, 3.09));
    expect(maxAbsZ).toBeLessThan(5);
  });

  it('diffuse transmission 0 is no extension, bit for bit', async () => {
    const a = renderSampled(await leafScene(null), { spp: 8, seed: 12 });
    const b = renderSampled(await leafScene(0), { spp: 8, seed: 12 });
    expect(Array.from(a.mean)).toEqual(Array.from(b.mean));
  });
});
