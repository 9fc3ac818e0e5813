/**
 * Denoising features (integrator/aux.ts): each material's albedo is what docs/film-format.md
 * defines, the normal is the shading normal facing the ray, the aux planes are exact sums
 * over the radiance's own samples (any row split gives the same bits), and a film with aux
 * gives the radiance of a film without.
 */
import { describe, expect, it } from 'vitest';
import { Document } from '@gltf-transform/core';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  parseScene,
  type Scene,
} from '../../../src/core/index.ts';
import { AuxSample, gltfAlbedo } from '../../../src/core/integrator/aux.ts';
import { ShadingParams } from '../../../src/core/bsdf/shading.ts';
import { docWith, png, quadPrimitive, sceneWithFiles, toGlb } from '../../helpers/gltf.ts';

const W = 8;
const H = 8;

/** A 4×4 quad at z = 0 facing −z (towards the camera at z = −3), filling the view. */
function wallScene(material: object, extra: { environment?: number[]; front?: object } = {}) {
  const shapes: object[] = [
    { type: 'quad', corner: [-2, -2, 0], u: [0, 4, 0], v: [4, 0, 0], material: 'm' },
  ];
  const materials: Record<string, object> = { m: material };
  if (extra.front) {
    materials.f = extra.front;
    // A 1.5×1.5 quad at z = −1 in front of the wall, filling the view too.
    shapes.push({
      type: 'quad',
      corner: [-1.5, -1.5, -1],
      u: [0, 3, 0],
      v: [3, 0, 0],
      material: 'f',
    });
  }
  return parseScene(
    JSON.stringify({
      format: 'pathwise-scene/1',
      camera: { position: [0, 0, -3], target: [0, 0, 0], up: [0, 1, 0], fovY: 20 },
      settings: { width: W, height: H, maxBounces: 4, spp: 4 },
      materials,
      shapes,
      environment: extra.environment ?? [0, 0, 0],
    }),
  );
}

function renderAux(scene: Scene, spp: number, sampler?: 'independent' | 'sobol') {
  const tracer = new PathTracer(compileScene(scene), {
    width: W,
    height: H,
    maxBounces: scene.settings.maxBounces,
    seed: 3,
    sampler,
    camera: scene.camera,
  });
  const film = new Film(W, H, undefined, 0, 0, true);
  const stats = new RenderStats();
  tracer.renderRows(film, 0, H, 0, spp, stats);
  return { film, tracer, stats, albedo: film.auxMean(0), normal: film.auxMean(3) };
}

/** Every pixel's value of an RGB image equals `rgb` exactly (as float32). */
function expectEverywhere(image: Float32Array, rgb: number[]): void {
  const want = rgb.map((v) => Math.fround(v));
  for (let p = 0; p < image.length / 3; p++) {
    expect([image[3 * p], image[3 * p + 1], image[3 * p + 2]]).toEqual(want);
  }
}

describe('aux albedo and normal per material', () => {
  it('a diffuse wall: its albedo and its normal, exactly', () => {
    const { albedo, normal, stats } = renderAux(
      wallScene({ type: 'diffuse', albedo: [0.8, 0.5, 0.25] }),
      4,
    );
    expectEverywhere(albedo, [0.8, 0.5, 0.25]);
    // The quad's normal is u × v = −z, towards the camera.
    expectEverywhere(normal, [0, 0, -1]);
    expect(stats.rejected).toBe(0);
  });

  it('the normal faces the ray: a wall seen from behind its normal gives the flipped one', () => {
    const scene = wallScene({ type: 'diffuse', albedo: [0.5, 0.5, 0.5] });
    // v × u: the same quad with its normal along +z, away from the camera.
    scene.shapes[0] = { ...scene.shapes[0], u: [4, 0, 0], v: [0, 4, 0] } as Scene['shapes'][0];
    expectEverywhere(renderAux(scene, 2).normal, [0, 0, -1]);
  });

  it('a rough metal: its specular colour', () => {
    const { albedo } = renderAux(
      wallScene({ type: 'conductor', color: [0.9, 0.6, 0.3], roughness: 0.4 }),
      4,
    );
    expectEverywhere(albedo, [0.9, 0.6, 0.3]);
  });

  it('an emitter: its emission added and clamped to 1; a dim emitter adds to its albedo', () => {
    const light = renderAux(
      wallScene({ type: 'diffuse', albedo: [0, 0, 0], emission: [5, 0.25, 0] }),
      2,
    );
    expectEverywhere(light.albedo, [1, 0.25, 0]);
    const dim = renderAux(
      wallScene({ type: 'diffuse', albedo: [0.5, 0.5, 0.5], emission: [0.25, 0, 0.75] }),
      2,
    );
    expectEverywhere(dim.albedo, [0.75, 0.5, 1]);
  });

  it('the environment: its radiance clamped to [0, 1], normal 0', () => {
    const scene = wallScene({ type: 'diffuse', albedo: [1, 1, 1] }, { environment: [3, 0.5, 0] });
    scene.shapes = [];
    const { albedo, normal } = renderAux(scene, 2);
    expectEverywhere(albedo, [1, 0.5, 0]);
    expectEverywhere(normal, [0, 0, 0]);
  });

  it('a mirror in front of a wall: the wall seen in it, times the mirror colour', () => {
    // The mirror faces the camera squarely: every camera ray comes back to the camera side
    // and escapes into the environment (0.5 grey), weighted by the Fresnel colour at that angle.
    const { albedo, normal } = renderAux(
      wallScene(
        { type: 'diffuse', albedo: [1, 1, 1] },
        {
          environment: [0.5, 0.5, 0.5],
          front: { type: 'conductor', color: [0.9, 0.9, 0.9], roughness: 0 },
        },
      ),
      2,
    );
    for (let p = 0; p < W * H; p++) {
      for (let c = 0; c < 3; c++) {
        // Schlick with F0 0.9 at the small angles of a 20° view: 0.45 to 0.4501.
        expect(albedo[3 * p + c]).toBeGreaterThanOrEqual(Math.fround(0.45));
        expect(albedo[3 * p + c]).toBeLessThan(0.4501);
      }
      // The normal is the mirror's: the last surface of the chain.
      expect([normal[3 * p], normal[3 * p + 1], normal[3 * p + 2]]).toEqual([0, 0, -1]);
    }
  });

  it('glass in front of a wall: the wall through it (Fresnel blend with what it reflects)', () => {
    // Each sample follows refraction (the wall's albedo 0.6, times the tint 1 — not the
    // radiance's 1/η²) or reflection (back to a black environment: 0), as the path's lobe
    // number chose. Independent samples: the count of refractions is binomial with
    // p = 1 − F, F ≈ 0.04 at near-normal incidence (ior 1.5).
    const n = 64;
    const { film } = renderAux(
      wallScene(
        { type: 'diffuse', albedo: [0.6, 0.6, 0.6] },
        { front: { type: 'dielectric', ior: 1.5, color: [1, 1, 1], roughness: 0 } },
      ),
      n,
      'independent',
    );
    const albedo = film.auxMean(0);
    let mean = 0;
    for (let p = 0; p < W * H; p++) mean += albedo[3 * p] / (W * H);
    // 4096 samples: σ of the refracted fraction = √(0.04·0.96/4096) ≈ 0.0031; ±5σ
    // (false alarm < 1e-6) on 0.6·(1 − F) with F between 0.0400 and 0.0405 here.
    expect(Math.abs(mean - 0.6 * 0.96) / 0.6).toBeLessThan(5 * 0.0031);
    // Per pixel, the mean is k·0.6/n for a count k of refractions: a multiple of 0.6/n.
    for (let p = 0; p < W * H; p++) {
      const k = (albedo[3 * p] * n) / 0.6;
      expect(Math.abs(k - Math.round(k))).toBeLessThan(1e-4);
    }
  });

  it('a textured glTF surface: base colour factor × texture (linear), and its normal', async () => {
    const doc = new Document();
    doc.createBuffer();
    // sRGB 128 everywhere: linear (128/255 + 0.055)/1.055)^2.4 ≈ 0.21586.
    const tex = doc
      .createTexture()
      .setImage(png(2, 2, () => [128, 64, 255, 255]))
      .setMimeType('image/png');
    const mat = doc
      .createMaterial()
      .setBaseColorFactor([0.5, 1, 0.25, 1])
      .setBaseColorTexture(tex)
      .setMetallicFactor(0)
      .setRoughnessFactor(0.7);
    const glb = await toGlb(docWith(doc, quadPrimitive(doc).setMaterial(mat)));
    const scene = await sceneWithFiles(
      {
        format: 'pathwise-scene/1',
        camera: { position: [0.5, 0.5, 3], target: [0.5, 0.5, 0], up: [0, 1, 0], fovY: 10 },
        settings: { width: W, height: H, maxBounces: 2, spp: 2 },
        materials: {},
        shapes: [{ type: 'gltf', file: 'm.glb' }],
        environment: [1, 1, 1],
      },
      new Map([['m.glb', glb]]),
    );
    const { albedo, normal } = renderAux(scene, 2);
    const lin = (v: number) => ((v / 255 + 0.055) / 1.055) ** 2.4;
    const want = [0.5 * lin(128), 1 * lin(64), 0.25 * lin(255)];
    for (let p = 0; p < W * H; p++) {
      for (let c = 0; c < 3; c++) expect(albedo[3 * p + c]).toBeCloseTo(want[c], 5);
      expect([normal[3 * p], normal[3 * p + 1], normal[3 * p + 2]]).toEqual([0, 0, 1]);
    }
  });
});

describe('alpha: the aux sees what the radiance sees', () => {
  it('a half-transparent emitter at 1 spp: albedo where the path hit it, 0 where it passed', async () => {
    const doc = new Document();
    doc.createBuffer();
    // Black base (albedo 0), emission 1, coverage 0.5: a sample that hits it has radiance 1
    // (bounces 0: emission only) and albedo 1; one that passes through sees the black
    // environment, radiance 0 and albedo 0.
    const mat = doc
      .createMaterial()
      .setBaseColorFactor([0, 0, 0, 0.5])
      .setAlphaMode('BLEND')
      .setEmissiveFactor([1, 1, 1]);
    const glb = await toGlb(docWith(doc, quadPrimitive(doc).setMaterial(mat)));
    const scene = await sceneWithFiles(
      {
        format: 'pathwise-scene/1',
        camera: { position: [0.5, 0.5, 3], target: [0.5, 0.5, 0], up: [0, 1, 0], fovY: 10 },
        settings: { width: 16, height: 16, maxBounces: 0, spp: 1 },
        materials: {},
        shapes: [{ type: 'gltf', file: 'm.glb' }],
        environment: [0, 0, 0],
      },
      new Map([['m.glb', glb]]),
    );
    const tracer = new PathTracer(compileScene(scene), {
      width: 16,
      height: 16,
      maxBounces: 0,
      seed: 5,
      camera: scene.camera,
    });
    const film = new Film(16, 16, undefined, 0, 0, true);
    tracer.renderRows(film, 0, 16, 0, 1, new RenderStats());
    const albedo = film.auxMean(0);
    const radiance = film.mean();
    let hits = 0;
    for (let p = 0; p < 256; p++) {
      const hit = radiance[3 * p] > 0;
      expect(albedo[3 * p], `pixel ${p}`).toBe(hit ? 1 : 0);
      if (hit) hits++;
    }
    // Both kinds occur (256 samples at p = 0.5: all of one kind has probability 2^-255).
    expect(hits).toBeGreaterThan(0);
    expect(hits).toBeLessThan(256);
  });
});

describe('gltfAlbedo: the layer sum', () => {
  const sp = () => {
    const s = new ShadingParams();
    s.baseR = 0.2;
    s.baseG = 0.4;
    s.baseB = 0.8;
    return s;
  };
  const albedo = (s: ShadingParams) => {
    const a = new AuxSample();
    gltfAlbedo(s, a);
    return [a.ar, a.ag, a.ab];
  };
  it('the base colour for dielectric, metal and transmissive bases alike', () => {
    const s = sp();
    expect(albedo(s)).toEqual([0.2, 0.4, 0.8]);
    s.metallic = 1;
    expect(albedo(s)).toEqual([0.2, 0.4, 0.8]);
    s.metallic = 0;
    s.transmission = 1;
    expect(albedo(s)).toEqual([0.2, 0.4, 0.8]);
  });
  it('a full white sheen is white; a clear coat adds its F0 share; unlit is its colour', () => {
    const s = sp();
    s.sheenR = s.sheenG = s.sheenB = 1;
    expect(albedo(s)).toEqual([1, 1, 1]);
    const c = sp();
    c.clearcoat = 1;
    const [r] = albedo(c);
    expect(r).toBeCloseTo(0.04 + 0.96 * 0.2, 15);
    const u = sp();
    u.unlit = true;
    u.clearcoat = 1;
    expect(albedo(u)).toEqual([0.2, 0.4, 0.8]);
  });
  it('diffuse transmission blends toward its colour by its weight', () => {
    const s = sp();
    s.diffuseTransmission = 0.5;
    s.dtR = s.dtG = s.dtB = 1;
    const a = albedo(s);
    expect(a[0]).toBeCloseTo(0.6, 15);
    expect(a[2]).toBeCloseTo(0.9, 15);
  });
});

describe('aux planes accumulate like radiance', () => {
  it('the radiance of a film with aux is bit-identical to a film without', async () => {
    const { readFileSync } = await import('node:fs');
    const { ROOT } = await import('../../helpers/render.ts');
    const s = parseScene(readFileSync(`${ROOT}scenes/mirror.json`, 'utf8'));
    const make = () =>
      new PathTracer(compileScene(s), {
        width: 12,
        height: 12,
        maxBounces: 6,
        seed: 1,
        camera: s.camera,
      });
    const plain = new Film(12, 12);
    const aux = new Film(12, 12, undefined, 0, 0, true);
    make().renderRows(plain, 0, 12, 0, 3, new RenderStats());
    make().renderRows(aux, 0, 12, 0, 3, new RenderStats());
    expect(aux.hi).toEqual(plain.hi);
    expect(aux.lo).toEqual(plain.lo);
    expect(aux.sums).toEqual(plain.sums);
    // And the aux planes are not empty: the scene has surfaces.
    expect(aux.auxHi!.some((v) => v !== 0) || aux.auxLo!.some((v) => v !== 0)).toBe(true);
  });
  it('rows and sample ranges split and added in any grouping give the same aux bits', async () => {
    const { readFileSync } = await import('node:fs');
    const { ROOT } = await import('../../helpers/render.ts');
    const s = parseScene(readFileSync(`${ROOT}scenes/mirror.json`, 'utf8'));
    const tracer = new PathTracer(compileScene(s), {
      width: 10,
      height: 10,
      maxBounces: 6,
      seed: 1,
      camera: s.camera,
    });
    const one = new Film(10, 10, undefined, 0, 0, true);
    tracer.renderRows(one, 0, 10, 0, 5, new RenderStats());
    const split = new Film(10, 10, undefined, 0, 0, true);
    for (const [y0, y1, s0, s1] of [
      [0, 3, 2, 5],
      [3, 10, 0, 1],
      [0, 3, 0, 2],
      [3, 10, 1, 5],
    ]) {
      const part = new Film(10, y1 - y0, undefined, y0, 0, true);
      tracer.renderRows(part, y0, y1, s0, s1, new RenderStats());
      split.add(part);
    }
    expect(split.auxHi).toEqual(one.auxHi);
    expect(split.auxLo).toEqual(one.auxLo);
    expect(split.hi).toEqual(one.hi);
    expect(() => split.add(new Film(10, 10))).toThrow(/albedo and normal/);
  });
  it('a non-finite aux value rejects the whole sample, counted', () => {
    const film = new Film(2, 1, undefined, 0, 0, true);
    const a = new AuxSample();
    a.nx = NaN;
    expect(film.addSampleAux(0, 0, { lr: 1, lg: 1, lb: 1 }, a)).toBe(false);
    expect(film.sums[3]).toBe(0);
    expect(film.hi.every((v) => v === 0)).toBe(true);
    a.nx = 0;
    a.ar = 0.5;
    expect(film.addSampleAux(0, 0, { lr: 1, lg: 1, lb: 1 }, a)).toBe(true);
    expect(film.auxMean(0)[0]).toBe(0.5);
  });
});
