/**
 * Scene files written from docs/scene-format.md (`pathwise-scene/1`): a camera, settings,
 * every material type, spheres, quads and inline meshes with transforms, a constant
 * environment; mutations of the JSON (a hostile value anywhere, a key deleted or added),
 * of its text (duplicate keys, comments, a BOM, deep nesting) and the magnitudes the format
 * allows but arithmetic may not (rotationY 1e308: issue 27 item 2).
 */
import { ByteWriter, ascii } from './bytes.ts';
import { mutateJson } from './mutate.ts';
import type { Rng } from './rng.ts';
import { CAMERA } from './scene-wrap.ts';
import type { Generator, Mutation, Sample } from './types.ts';

/** A 1 × 1 white PFM (little-endian) for the environment-map mutations to name. */
const WHITE_PFM = new ByteWriter()
  .text('PF\n1 1\n-1.0\n')
  .f32(1, true)
  .f32(1, true)
  .f32(1, true)
  .done();

type Scene = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

function randomScene(rng: Rng): Scene {
  const materials: Scene = {
    matte: { type: 'diffuse', albedo: [rng.float(0, 1), 0.5, 0.5] },
    metal: { type: 'conductor', color: [0.9, 0.8, 0.5], roughness: rng.float(0, 1) },
    glass: { type: 'dielectric', ior: rng.float(1.1, 2), color: [1, 1, 1] },
    lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [5, 5, 4] },
  };
  const names = ['matte', 'metal', 'glass'];
  const shapes: unknown[] = [
    { type: 'quad', corner: [0.8, -1.2, 1], u: [0, 0.6, 0], v: [0.6, 0, 0], material: 'lamp' },
  ];
  for (let i = rng.range(1, 4); i > 0; i--) {
    const kind = rng.pick(['sphere', 'quad', 'mesh']);
    const material = rng.pick(names);
    if (kind === 'sphere')
      shapes.push({
        type: 'sphere',
        center: [rng.float(-1, 1), rng.float(-1, 1), rng.float(-1, 1)],
        radius: rng.float(0.1, 0.8),
        material,
      });
    else if (kind === 'quad')
      shapes.push({ type: 'quad', corner: [-2, -1, -2], u: [4, 0, 0], v: [0, 0, 4], material });
    else {
      const mesh: Scene = {
        type: 'mesh',
        material,
        positions: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1],
        indices: [0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2],
      };
      if (rng.chance(0.5)) mesh.transform = [1, 0, 0, -0.5, 0, 1, 0, -0.3, 0, 0, 1, 0, 0, 0, 0, 1];
      if (rng.chance(0.3)) mesh.normals = [0, 0, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1];
      shapes.push(mesh);
    }
  }
  const scene: Scene = {
    format: 'pathwise-scene/1',
    name: 'spec-fuzz',
    camera: { ...CAMERA, ...(rng.chance(0.3) ? { aperture: 0.02, focusDistance: 4 } : {}) },
    materials,
    shapes,
    environment: [0.2, 0.3, rng.float(0.1, 0.6)],
  };
  if (rng.chance(0.5))
    scene.settings = { width: 64, height: 48, maxBounces: rng.range(0, 8), spp: 4 };
  return scene;
}

function mutations(scene: Scene): Mutation[] {
  const text = (s: Scene) => ascii(JSON.stringify(s, null, 1));
  const j = (name: string, f: (s: Scene, rng: Rng) => void): Mutation => ({
    name: `scene:${name}`,
    apply: (rng) => {
      const s = structuredClone(scene);
      f(s, rng);
      return { 'scene.json': text(s) };
    },
  });
  const raw = (name: string, f: (t: string, rng: Rng) => string): Mutation => ({
    name: `scene:${name}`,
    apply: (rng) => ({ 'scene.json': ascii(f(JSON.stringify(scene, null, 1), rng)) }),
  });
  return [
    j('json-random', (s, r) => Object.assign(s, mutateJson(s, r).json)),
    j('json-random', (s, r) => Object.assign(s, mutateJson(s, r).json)),
    j('json-random-3', (s, r) => {
      let v: unknown = s;
      for (let k = 0; k < 3; k++) v = mutateJson(v, r).json;
      Object.assign(s, v);
    }),
    j('rotation-1e308', (s, r) => {
      s.environment = { type: 'map', file: 'sky.pfm', rotationY: r.pick([1e308, -1e308, 1.7e308]) };
    }),
    j('camera-far', (s, r) => void (s.camera.position = [r.pick([1e308, -1e308]), 0, 0])),
    j('camera-target-equals-position', (s) => void (s.camera.target = [...s.camera.position])),
    j('camera-up-parallel', (s) => void (s.camera.up = [0, 4.3, 4])),
    j('fov-edge', (s, r) => void (s.camera.fovY = r.pick([0, 180, 1e-300, 179.9999999]))),
    j(
      'huge-sphere',
      (s, r) =>
        void s.shapes.push({
          type: 'sphere',
          center: [0, 0, 0],
          radius: r.pick([1e308, 1e200, 1e-300]),
          material: 'matte',
        }),
    ),
    j(
      'mesh-index-out-of-range',
      (s) =>
        void s.shapes.push({
          type: 'mesh',
          material: 'matte',
          positions: [0, 0, 0, 1, 0, 0, 0, 1, 0],
          indices: [0, 1, 3],
        }),
    ),
    j(
      'mesh-huge-coordinates',
      (s) =>
        void s.shapes.push({
          type: 'mesh',
          material: 'matte',
          positions: [1.7e308, 0, 0, -1.7e308, 0, 0, 0, 1.7e308, 0],
        }),
    ),
    j(
      'transform-singular',
      (s) =>
        void s.shapes.push({
          type: 'mesh',
          material: 'matte',
          positions: [0, 0, 0, 1, 0, 0, 0, 1, 0],
          transform: [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1],
        }),
    ),
    j(
      'transform-overflow',
      (s) =>
        void s.shapes.push({
          type: 'mesh',
          material: 'matte',
          positions: [0, 0, 0, 1, 0, 0, 0, 1, 0],
          transform: [1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1],
        }),
    ),
    j('emission-huge', (s) => void (s.materials.lamp.emission = [1e12, 1e12, 1e12])),
    j('many-shapes', (s) => {
      for (let i = 0; i < 20000; i++)
        s.shapes.push({ type: 'sphere', center: [i % 7, 0, 3], radius: 0.01, material: 'matte' });
    }),
    j('env-map-missing', (s) => void (s.environment = { type: 'map', file: 'none.hdr' })),
    j('env-map-directory', (s) => void (s.environment = { type: 'map', file: '.' })),
    j(
      'mesh-file-self',
      (s) => void s.shapes.push({ type: 'mesh', material: 'matte', file: 'scene.json' }),
    ),
    j('gltf-file-self', (s) => void s.shapes.push({ type: 'gltf', file: 'scene.json' })),
    j(
      'unknown-key',
      (s, r) => void (s[r.pick(['extra', '__proto__', 'constructor'])] = { polluted: true }),
    ),
    raw('duplicate-key', (t) =>
      t.replace(
        '"format": "pathwise-scene/1"',
        '"format": "pathwise-scene/1", "format": "pathwise-scene/1"',
      ),
    ),
    raw('comment', (t) => `// a comment\n${t}`),
    raw('trailing-comma', (t) => t.replace(/\]\s*\n(\s*)\}/, '],\n$1}')),
    raw('bom', (t) => `\ufeff${t}`),
    raw('deep-nesting', (t) =>
      t.replace('"name": "spec-fuzz"', `"name": ${'['.repeat(100000)}${']'.repeat(100000)}`),
    ),
    raw('big-number-literal', (t) => t.replace(/"radius": [0-9.e-]+/, '"radius": 1e400')),
    raw('lone-surrogate', (t) => t.replace('"spec-fuzz"', '"\\ud800"')),
    raw('nul-in-string', (t) => t.replace('"spec-fuzz"', '"spec\\u0000fuzz"')),
    raw('truncated', (t, r) => t.slice(0, r.int(t.length))),
  ];
}

export const sceneGenerator: Generator = {
  format: 'scene',
  generate(rng: Rng): Sample {
    const scene = randomScene(rng);
    return {
      variant: `${scene.shapes.length - 1} shapes`,
      files: {
        'scene.json': ascii(JSON.stringify(scene, null, 1)),
        'sky.pfm': WHITE_PFM,
      },
      target: 'scene.json',
      args: ['render', 'scene.json'],
      lit: false,
      mutations: mutations(scene),
    };
  },
};
