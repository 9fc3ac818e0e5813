/**
 * Finite values whose derived quantities overflow (issue 27, finding 2), and values of
 * the wrong type named by their type (finding 4): every sample of a render was dropped,
 * or the picture was silently wrong, though each number of the scene was finite.
 * - Light selection weights: an emitter of radiance 10¹² and area 10³⁰⁰ has a power of
 *   Infinity, and with a second light the selection CDF became NaN.
 * - The environment map's power through a scene 10³⁰⁰ across: integral × r², Infinity.
 * - A thin lens of aperture 1e308: the direction's squared length overflowed and the
 *   camera made rays with no direction. A lens that reaches beyond the double range from
 *   the camera's position is refused by path.
 * (environment.rotationY 1e308 is reduced modulo 360 exactly before it becomes radians:
 * tests/fuzz/magnitudes.test.ts, docs/scene-format.md.)
 */
import { describe, expect, it } from 'vitest';
import {
  compileScene,
  encodePfm,
  Film,
  parseScene,
  PathTracer,
  RenderStats,
  SceneError,
  type Scene,
} from '../../../src/core/index.ts';
import { Camera } from '../../../src/core/camera/camera.ts';
import { Ray } from '../../../src/core/geometry/ray.ts';
import { sceneWithFiles } from '../../helpers/gltf.ts';

function base(): Record<string, any> {
  return {
    format: 'pathwise-scene/1',
    settings: { width: 8, height: 8, spp: 1, maxBounces: 3 },
    camera: { position: [0, 0, 5], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
    materials: {
      grey: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [1e12, 1e12, 1e12] },
      bulb: { type: 'diffuse', albedo: [0, 0, 0], emission: [4, 4, 4] },
    },
    shapes: [{ type: 'sphere', center: [0, 0, 0], radius: 1, material: 'grey' }],
    environment: [0, 0, 0],
  };
}

/** One sample per pixel: the samples dropped as non-finite, and whether any pixel is lit. */
function render(scene: Scene) {
  const { width, height, maxBounces } = scene.settings;
  const film = new Film(width, height);
  const stats = new RenderStats();
  new PathTracer(compileScene(scene), {
    width,
    height,
    maxBounces,
    seed: 1,
    camera: scene.camera,
  }).renderRows(film, 0, height, 0, 1, stats);
  const mean = film.mean();
  return {
    rejected: stats.rejected,
    lit: mean.some((v) => v > 0),
    finite: mean.every(Number.isFinite),
  };
}

describe('light powers that overflow', () => {
  it('an emitter whose power is Infinity beside another light: no sample dropped', () => {
    const s = base();
    // Power 1e12 × 4π × (1e150)² overflows; the sphere is far away above the scene.
    s.shapes.push({ type: 'sphere', center: [0, 1e152, 0], radius: 1e150, material: 'lamp' });
    s.shapes.push({
      type: 'quad',
      corner: [-1, 3, -1],
      u: [2, 0, 0],
      v: [0, 0, 2],
      material: 'bulb',
    });
    const r = render(parseScene(JSON.stringify(s)));
    expect(r.rejected).toBe(0);
    expect(r.finite).toBe(true);
    expect(r.lit).toBe(true);
  });

  it('an environment map around a scene 1e300 across, with a lamp: no sample dropped', async () => {
    const s = base();
    s.shapes.push({ type: 'sphere', center: [0, -1e300, 0], radius: 1, material: 'grey' });
    s.shapes.push({
      type: 'quad',
      corner: [-1, 3, -1],
      u: [2, 0, 0],
      v: [0, 0, 2],
      material: 'bulb',
    });
    s.environment = { type: 'map', file: 'sky.pfm' };
    const files = new Map([['sky.pfm', encodePfm(4, 2, new Float32Array(24).fill(0.5))]]);
    const scene = await sceneWithFiles(s, files);
    // Before: weights [8, Infinity]. Now relative to the largest: the lamp's share,
    // 2^-1997 of the map's, is below the double range, as it truly is negligible.
    const power = Array.from(compileScene(scene).data.lightPower);
    expect(power).toEqual([0, 1]);
    const r = render(scene);
    expect(r.rejected).toBe(0);
    expect(r.finite).toBe(true);
    expect(r.lit).toBe(true);
  });

  it('keeps the weights of ordinary scenes bit for bit', () => {
    const s = base();
    s.shapes.push({
      type: 'quad',
      corner: [-1, 3, -1],
      u: [2, 0, 0],
      v: [0, 0, 2],
      material: 'bulb',
    });
    s.shapes.push({ type: 'sphere', center: [3, 3, 0], radius: 0.5, material: 'bulb' });
    const power = compileScene(parseScene(JSON.stringify(s))).data.lightPower;
    const lum = 4; // luminance of emission (4, 4, 4)
    expect(Array.from(power)).toEqual([lum * 4 * Math.PI * 0.5 * 0.5, lum * 4]);
  });
});

describe('a thin lens near the double range', () => {
  it('aperture 1e308 makes finite unit directions, not rays with none', () => {
    const camera = new Camera(
      {
        position: [0, 0, 5],
        target: [0, 0, 0],
        up: [0, 1, 0],
        fovY: 40,
        aperture: 1e308,
        focusDistance: 5,
      },
      8,
      8,
    );
    const ray = new Ray();
    for (const [u, v] of [
      [0.9, 0.5],
      [0.1, 0.2],
      [0.5, 0.99],
    ]) {
      camera.generateRay(4, 4, u, v, ray);
      const len = Math.hypot(ray.dx, ray.dy, ray.dz);
      expect(len, `lens (${u}, ${v})`).toBeCloseTo(1, 12);
      expect(Number.isFinite(ray.ox) && Number.isFinite(ray.oy) && Number.isFinite(ray.oz)).toBe(
        true,
      );
    }
  });

  it('a lens that reaches beyond the double range from the position is refused by path', () => {
    const s = base();
    s.camera = { ...s.camera, position: [0, 0, 1e308], target: [0, 0, 0], aperture: 1e308 };
    let problems: string[] = [];
    try {
      parseScene(JSON.stringify(s));
    } catch (e) {
      problems = (e as SceneError).problems;
    }
    expect(problems).toEqual([
      'camera.aperture 1e+308 and camera.focusDistance 1e+308 reach beyond the double range from ' +
        'camera.position [0, 0, 1e+308]: |position.x| + aperture + focusDistance = Infinity',
    ]);
  });
});

describe('values of the wrong type are named by their type', () => {
  function problemsOf(s: Record<string, any>): string[] {
    try {
      parseScene(JSON.stringify(s));
    } catch (e) {
      return (e as SceneError).problems;
    }
    return [];
  }

  it('the string "0", an object, an array', () => {
    const s = base();
    s.shapes[0].radius = '0';
    s.camera.fovY = {};
    s.materials.grey.albedo = 'grey';
    expect(problemsOf(s)).toEqual(
      expect.arrayContaining([
        'shapes[0].radius must be a finite number, got the string "0" (numbers must not be quoted)',
        'camera.fovY must be a finite number, got an object',
        'materials.grey.albedo must be an array of 3 numbers, got the string "grey"',
      ]),
    );
  });

  it('never as [object Object], whatever value replaces whatever field', () => {
    const template = {
      ...base(),
      shapes: [
        { type: 'sphere', center: [0, 0, 0], radius: 1, material: 'grey' },
        { type: 'quad', corner: [0, 0, 0], u: [1, 0, 0], v: [0, 1, 0], material: 'bulb' },
        {
          type: 'mesh',
          material: 'grey',
          positions: [0, 0, 0, 1, 0, 0, 0, 1, 0],
          indices: [0, 1, 2],
        },
        {
          type: 'mesh',
          material: 'grey',
          file: 'a.obj',
          transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
        },
        { type: 'gltf', file: 'a.glb' },
      ],
      environment: { type: 'map', file: 'sky.hdr', scale: [1, 1, 1], rotationY: 0 },
    };
    const paths: (string | number)[][] = [];
    const walk = (v: unknown, p: (string | number)[]) => {
      if (p.length > 0) paths.push(p);
      if (v !== null && typeof v === 'object') {
        for (const [k, x] of Object.entries(v)) walk(x, [...p, Array.isArray(v) ? Number(k) : k]);
      }
    };
    walk(template, []);
    const seen: string[] = [];
    for (const p of paths) {
      for (const value of [{}, { a: 1 }, '0', [[]], [{}], [{}, {}, {}], true, null, [1, {}, 3]]) {
        const s = structuredClone(template) as Record<string | number, any>;
        let o = s;
        for (const k of p.slice(0, -1)) o = o[k];
        o[p[p.length - 1]] = value;
        for (const m of problemsOf(s)) {
          if (/\[object|undefined|NaN/.test(m))
            seen.push(`${p.join('.')} = ${JSON.stringify(value)}: ${m}`);
        }
      }
    }
    expect(seen).toEqual([]);
  });
});
