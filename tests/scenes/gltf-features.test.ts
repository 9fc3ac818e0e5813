/**
 * glTF features in whole renders, each checked against an answer that does not share
 * the code under test:
 * - alpha MASK renders like the geometry it cuts out (a quad half cut away by a mask
 *   against a quad of half the size), for the camera and for shadow rays;
 * - alpha BLEND: next-event estimation (shadow rays take the expected transmittance
 *   through the surface) agrees with BSDF sampling alone (paths decide stochastically);
 * - an emissive texture (with KHR_materials_emissive_strength): next-event
 *   estimation, which looks the texture up at the light sample, agrees with BSDF
 *   sampling alone, which finds it at hits;
 * - a rough transmissive solid: next-event estimation of its rough reflection, also
 *   from inside, agrees with BSDF sampling alone;
 * - a normal map tilts the diffuse lobe: a plane under a white upper hemisphere reads
 *   ρ(1 + cos α)/2 with α the tilt the texel encodes (both estimators).
 * Block tests as in gltf-reductions.test.ts (independent samples, 4×4 blocks, χ² at
 * p = 0.001, no |z| over 5); the closed form within 4 standard errors.
 */
import { Document } from '@gltf-transform/core';
import {
  KHRMaterialsEmissiveStrength,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsVolume,
} from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import type { EnvironmentMapDesc, Estimator, Scene } from '../../src/core/index.ts';
import { docWith, meshPrimitive, png, sceneWithFiles, toGlb } from '../helpers/gltf.ts';
import { cube } from '../helpers/mesh-gen.ts';
import { expectSameImage, imageMean, renderSampled } from '../helpers/render.ts';

const SIZE = 32;
const SPP = 64;

/** A Lambertian glTF material (no specular layer): it equals the diffuse material. */
function lambert(doc: Document, base: number[] = [0.8, 0.8, 0.8, 1]) {
  const spec = doc.createExtension(KHRMaterialsSpecular).createSpecular().setSpecularFactor(0);
  return doc
    .createMaterial()
    .setBaseColorFactor(base as [number, number, number, number])
    .setMetallicFactor(0)
    .setRoughnessFactor(1)
    .setExtension('KHR_materials_specular', spec);
}

/**
 * A horizontal rectangle y = h, x and z in [x0, x0 + w] × [−d/2, d/2], facing `up` or
 * down, uv = ((x − x0)/w, z/d + 0.5).
 */
function square(doc: Document, h: number, x0: number, w: number, up: boolean, d = 1) {
  const z = d / 2;
  const positions = [x0, h, -z, x0 + w, h, -z, x0 + w, h, z, x0, h, z];
  const uv = [0, 0, 1, 0, 1, 1, 0, 1];
  // Counter-clockwise seen from +y is (0, 3, 2), (0, 2, 1).
  const indices = up ? [0, 3, 2, 0, 2, 1] : [0, 1, 2, 0, 2, 3];
  const n = up ? [0, 1, 0] : [0, -1, 0];
  return meshPrimitive(doc, positions, indices, { normals: [...n, ...n, ...n, ...n], uv });
}

/** Floor, a ceiling lamp (unless the glTF brings one), camera seeing the floor. */
function room(lamp: boolean, shapes: unknown[] = []) {
  return {
    format: 'pathwise-scene/1',
    camera: { position: [0, 2.2, 3], target: [0, 0.3, 0], up: [0, 1, 0], fovY: 45 },
    settings: { width: SIZE, height: SIZE, maxBounces: 4, spp: SPP },
    materials: {
      floor: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
      grey: { type: 'diffuse', albedo: [0.8, 0.8, 0.8] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [1.5, 1.5, 1.5] },
      bright: { type: 'diffuse', albedo: [0, 0, 0], emission: [8, 8, 8] },
    },
    shapes: [
      { type: 'quad', corner: [-2, 0, 2], u: [4, 0, 0], v: [0, 0, -4], material: 'floor' },
      ...(lamp
        ? [
            {
              type: 'quad',
              corner: [-2, 3, -2],
              // Facing down (u × v points to −y), and large: BSDF sampling alone finds
              // it often enough for its sample variance to be a fair estimate.
              u: [4, 0, 0],
              v: [0, 0, 4],
              material: 'lamp',
            },
          ]
        : []),
      ...shapes,
    ],
    environment: [0.2, 0.2, 0.2],
  };
}

async function withGltf(doc: Document, json: ReturnType<typeof room>): Promise<Scene> {
  json.shapes.push({ type: 'gltf', file: 'm.glb' } as never);
  return sceneWithFiles(json, new Map([['m.glb', await toGlb(doc)]]));
}

function render(scene: Scene, seed: number, estimator?: Estimator) {
  return renderSampled(scene, { spp: SPP, seed, estimator, sampler: 'independent' });
}

function expectSame(a: ReturnType<typeof render>, b: ReturnType<typeof render>): void {
  expectSameImage(a, b);
}

describe('alpha in the tracer', () => {
  it('MASK renders like the geometry it leaves: half a quad cut away by a mask', async () => {
    // A 2×1 texture, left texel transparent, right opaque: bilinear alpha crosses the
    // cutoff 0.5 exactly at u = 0.5, so the mask keeps x ∈ [−0.5, 0.5] of the quad
    // spanning [−1.5, 0.5]. Above the floor, under the lamp: it is seen and it shadows.
    const doc = new Document();
    const tex = doc
      .createTexture()
      .setImage(png(2, 1, (x) => [255, 255, 255, x === 0 ? 0 : 255]))
      .setMimeType('image/png');
    const mat = lambert(doc).setBaseColorTexture(tex).setAlphaMode('MASK').setAlphaCutoff(0.5);
    docWith(doc, square(doc, 1, -1.5, 2, true).setMaterial(mat));
    const masked = await withGltf(doc, room(true));
    const cut = await sceneWithFiles(
      room(true, [
        { type: 'quad', corner: [-0.5, 1, 0.5], u: [1, 0, 0], v: [0, 0, -1], material: 'grey' },
      ]),
      new Map(),
    );
    expectSame(render(masked, 1), render(cut, 2));
  });

  it('BLEND: shadow rays through it agree with paths that decide at random', async () => {
    const doc = new Document();
    const mat = lambert(doc, [0.9, 0.5, 0.2, 0.4]).setAlphaMode('BLEND');
    docWith(doc, square(doc, 1, -0.6, 1.2, true).setMaterial(mat));
    const scene = await withGltf(doc, room(true));
    expectSame(render(scene, 3, 'nee-mis'), render(scene, 4, 'bsdf'));
  });
});

describe('emissive textures', () => {
  it('light sampling agrees with BSDF sampling alone', async () => {
    // The lamp is a glTF ceiling facing down with a 2×2 emissive texture (one bright
    // corner, one dim, two dark): emission varies over the light and is zero in part.
    const doc = new Document();
    const tex = doc
      .createTexture()
      .setImage(
        png(2, 2, (x, y) =>
          x === 0 && y === 0
            ? [255, 200, 120, 255]
            : x === 1 && y === 1
              ? [60, 60, 60, 255]
              : [0, 0, 0, 255],
        ),
      )
      .setMimeType('image/png');
    const strength = doc
      .createExtension(KHRMaterialsEmissiveStrength)
      .createEmissiveStrength()
      .setEmissiveStrength(2);
    const mat = lambert(doc, [0, 0, 0, 1])
      .setEmissiveFactor([1, 1, 1])
      .setEmissiveTexture(tex)
      .setExtension('KHR_materials_emissive_strength', strength);
    docWith(doc, square(doc, 3, -2, 4, false, 4).setMaterial(mat));
    const scene = await withGltf(doc, room(false));
    scene.environment = [0.02, 0.02, 0.02];
    expectSame(render(scene, 5, 'nee-mis'), render(scene, 6, 'bsdf'));
  });
});

describe('rough transmissive glTF surfaces', () => {
  it('light sampling from inside and outside agrees with BSDF sampling alone', async () => {
    // A closed glass-like box (transmission 1, roughness 0.4) with a small lamp inside:
    // its rough reflection is light-sampled on both sides of the surface (from inside
    // toward the inner lamp), the refraction is not. A solid (KHR_materials_volume), as
    // this test was written for: glTF's default thin wall would let the lamp be seen
    // straight through, by caustic paths (floor → wall → lamp) that neither estimator
    // light-samples, whose rare large samples make 64 spp block variances unreliable.
    const doc = new Document();
    const tr = doc
      .createExtension(KHRMaterialsTransmission)
      .createTransmission()
      .setTransmissionFactor(1);
    const mat = doc
      .createMaterial()
      .setBaseColorFactor([0.9, 0.8, 0.7, 1])
      .setMetallicFactor(0)
      .setRoughnessFactor(0.4)
      .setExtension('KHR_materials_transmission', tr)
      .setExtension(
        'KHR_materials_volume',
        doc.createExtension(KHRMaterialsVolume).createVolume().setThicknessFactor(1),
      );
    const c = cube();
    const box = meshPrimitive(
      doc,
      Array.from(c.positions, (v, i) => (i % 3 === 1 ? v * 0.8 + 0.2 : v * 1.2 - 0.6)),
      c.indices,
    );
    docWith(doc, box.setMaterial(mat));
    const inner = { type: 'quad', corner: [-0.3, 0.4, 0.3], u: [0.6, 0, 0], v: [0, 0, -0.6] };
    // The only lamp (the environment aside), so that light sampling matters.
    const scene = await withGltf(doc, room(false, [{ ...inner, material: 'bright' }]));
    expectSame(render(scene, 7, 'nee-mis'), render(scene, 8, 'bsdf'));
  });
});

describe('normal maps in the tracer', () => {
  function horizonMap(): EnvironmentMapDesc {
    return {
      type: 'map',
      file: 'horizon.pfm',
      scale: [1, 1, 1],
      rotationY: 0,
      image: { width: 1, height: 2, rgb: Float32Array.from([1, 1, 1, 0, 0, 0]) },
    };
  }

  it('tilt the diffuse lobe: a plane under a white upper hemisphere reads ρ(1 + cos α)/2', async () => {
    // (Not 0: an 8-bit texel cannot encode exactly 0, and a tilt of 0.3° leaves
    // the sky unseen by 1 sample in 10^5, too rare for a sample variance.)
    for (const tilt of [Math.PI / 6, Math.PI / 4, Math.PI / 3]) {
      // Tangent space (sin α, 0, cos α): leaning toward +u, which runs along +x; the
      // file has no tangents, so MikkTSpace makes them.
      const code = [Math.sin(tilt), 0, Math.cos(tilt)].map((v) =>
        Math.round((v * 0.5 + 0.5) * 255),
      );
      const doc = new Document();
      const tex = doc
        .createTexture()
        .setImage(png(1, 1, () => [...code, 255]))
        .setMimeType('image/png');
      const mat = lambert(doc, [0.6, 0.6, 0.6, 1]).setNormalTexture(tex);
      const plane = meshPrimitive(
        doc,
        [-2, 0, -2, -2, 0, 2, 2, 0, 2, 2, 0, -2],
        [0, 1, 2, 0, 2, 3],
        {
          normals: [0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0],
          uv: [0, 0, 0, 1, 1, 1, 1, 0],
        },
      );
      docWith(doc, plane.setMaterial(mat));
      const json = {
        format: 'pathwise-scene/1',
        camera: { position: [0, 3, -0.5], target: [0, 0, 0], up: [0, 0, 1], fovY: 20 },
        settings: { width: 8, height: 8, maxBounces: 1, spp: 1 },
        materials: {},
        shapes: [{ type: 'gltf', file: 'm.glb' }],
      };
      const scene = await sceneWithFiles(json, new Map([['m.glb', await toGlb(doc)]]));
      scene.environmentMap = horizonMap();
      // What the 8-bit texel encodes: the world normal's y is its z over its length.
      const n = code.map((c) => (2 * c) / 255 - 1);
      const cos = n[2] / Math.hypot(n[0], n[1], n[2]);
      const expected = (0.6 * (1 + cos)) / 2;
      for (const estimator of ['bsdf', 'nee-mis'] as const) {
        const { mean, stderr } = imageMean(renderSampled(scene, { spp: 512, estimator }));
        expect(Math.abs(mean[0] - expected), `α ${tilt} ${estimator}`).toBeLessThan(
          4 * stderr[0] + 1e-12,
        );
      }
    }
  });
});
