/**
 * Punctual lights, everything but the light transport (tests/statistical/
 * punctual-lights.test.ts has that): KHR_lights_punctual read from glTF files (world
 * placement, defaults, the checks of the JSON), the scene format's `lights` (defaults
 * and one message per problem, naming the entry), the compiled light list (kinds,
 * selection by power), and samplePunctual's edge cases (range, cone, the light itself).
 */
import { Document } from '@gltf-transform/core';
import { KHRLightsPunctual } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { compileScene, parseScene, SceneError } from '../../../src/core/index.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import { LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT } from '../../../src/core/geometry/ray.ts';
import { LightSample } from '../../../src/core/lights/lights.ts';
import {
  compilePunctualLights,
  samplePunctual,
  spotAttenuation,
  spotAngleScale,
} from '../../../src/core/lights/punctual.ts';
import type { LightDesc } from '../../../src/core/scene/format/types.ts';
import { bareModelScene } from '../../../src/core/scene/load/bare-scene.ts';
import { loadGlb, memoryOptions, quadPrimitive } from '../../helpers/gltf.ts';

const close = (a: number[], b: number[], eps = 1e-12) =>
  a.forEach((x, i) =>
    expect(Math.abs(x - b[i]), `component ${i}: ${x} vs ${b[i]}`).toBeLessThan(eps),
  );

/** A quad and three lights: a spot looking down, a point in a scaled parent, a sun. */
function lightsDoc(): Document {
  const doc = new Document();
  const ext = doc.createExtension(KHRLightsPunctual);
  const spot = ext
    .createLight('spot')
    .setType('spot')
    .setIntensity(200)
    .setColor([1, 0.9, 0.8])
    .setRange(50)
    .setInnerConeAngle(0.2)
    .setOuterConeAngle(0.5);
  const point = ext.createLight('point').setType('point').setIntensity(50);
  const sun = ext.createLight('sun').setType('directional').setIntensity(2);
  const down = [-Math.SQRT1_2, 0, 0, Math.SQRT1_2] as [number, number, number, number];
  const scene = doc.createScene();
  scene.addChild(doc.createNode().setMesh(doc.createMesh().addPrimitive(quadPrimitive(doc))));
  scene.addChild(
    doc
      .createNode()
      .setTranslation([0, 4, 2])
      .setRotation(down)
      .setExtension('KHR_lights_punctual', spot),
  );
  // Scale moves a child light but never weakens it (the extension's "Adding Light
  // Instances to Nodes").
  const parent = doc.createNode().setScale([2, 2, 2]).setTranslation([1, 0, 0]);
  parent.addChild(
    doc.createNode().setTranslation([1, 1, 1]).setExtension('KHR_lights_punctual', point),
  );
  scene.addChild(parent);
  scene.addChild(
    doc.createNode().setRotation(down).setScale([3, 3, 3]).setExtension('KHR_lights_punctual', sun),
  );
  doc.getRoot().setDefaultScene(scene);
  return doc;
}

/** A .gltf holding only nodes and the extension, as JSON bytes. */
function jsonGltf(lights: unknown[], nodes: unknown[]): Uint8Array {
  return new TextEncoder().encode(
    JSON.stringify({
      asset: { version: '2.0' },
      extensionsUsed: ['KHR_lights_punctual'],
      extensions: { KHR_lights_punctual: { lights } },
      scenes: [{ nodes: nodes.map((_, i) => i) }],
      scene: 0,
      nodes,
    }),
  );
}

async function loadJson(lights: unknown[], nodes: unknown[]) {
  return loadGltf(jsonGltf(lights, nodes), 'lights.gltf', await memoryOptions());
}

describe('KHR_lights_punctual in glTF files', () => {
  it('places each light at its node in world space, with its colour, intensity, cone and range', async () => {
    const model = await loadGlb(lightsDoc());
    expect(model.warnings).toEqual([]);
    const [spot, point, sun] = model.lights!;
    expect(spot.type).toBe('spot');
    close(spot.position, [0, 4, 2]);
    // −z turned by −90° about x: straight down.
    close(spot.direction, [0, -1, 0]);
    expect(spot.intensity).toBe(200);
    close(spot.color, [1, 0.9, 0.8], 1e-7);
    close(
      [spot.innerConeAngle, spot.outerConeAngle],
      [0.2 * (180 / Math.PI), 0.5 * (180 / Math.PI)],
    );
    expect(spot.range).toBe(50);
    expect(point.type).toBe('point');
    close(point.position, [3, 2, 2]);
    expect(point.intensity).toBe(50);
    expect(point.range).toBeNull();
    expect(sun.type).toBe('directional');
    close(sun.direction, [0, -1, 0]);
    expect(sun.intensity).toBe(2);
  });

  it('fills the defaults of the extension: white, 1, cone 0 to π/4', async () => {
    const m = await loadJson(
      [{ type: 'spot' }, { type: 'point' }],
      [
        { extensions: { KHR_lights_punctual: { light: 0 } } },
        { extensions: { KHR_lights_punctual: { light: 1 } } },
      ],
    );
    const [spot, point] = m.lights!;
    expect(spot.color).toEqual([1, 1, 1]);
    expect(spot.intensity).toBe(1);
    close([spot.innerConeAngle, spot.outerConeAngle], [0, 45]);
    close(spot.direction, [0, 0, -1]);
    expect(point.position).toEqual([0, 0, 0]);
  });

  it('no longer reports the extension as ignored', async () => {
    const m = await loadJson(
      [{ type: 'point' }],
      [{ extensions: { KHR_lights_punctual: { light: 0 } } }],
    );
    expect(m.warnings.join('\n')).not.toContain('KHR_lights_punctual');
  });

  it.each([
    [
      [{ type: 'area' }],
      'extensions.KHR_lights_punctual.lights[0].type: must be one of "directional", "point", "spot", got the string "area"',
    ],
    [[{}], 'extensions.KHR_lights_punctual.lights[0].type: is required'],
    [
      [{ type: 'point', intensity: -1 }],
      'extensions.KHR_lights_punctual.lights[0].intensity: must be a finite number ≥ 0, got -1',
    ],
    [
      [{ type: 'point', color: [1, 1] }],
      'extensions.KHR_lights_punctual.lights[0].color: must be 3 finite numbers ≥ 0',
    ],
    [
      [{ type: 'point', range: 0 }],
      'extensions.KHR_lights_punctual.lights[0].range: must be a finite number > 0, got 0',
    ],
    [
      [{ type: 'directional', range: 3 }],
      'extensions.KHR_lights_punctual.lights[0].range: is allowed only on point and spot lights',
    ],
    [
      [{ type: 'spot', spot: { innerConeAngle: 0.6, outerConeAngle: 0.5 } }],
      'extensions.KHR_lights_punctual.lights[0].spot: innerConeAngle (0.6) must be less than outerConeAngle (0.5)',
    ],
    [
      [{ type: 'spot', spot: { outerConeAngle: 2 } }],
      'extensions.KHR_lights_punctual.lights[0].spot.outerConeAngle: must be a finite number in (0, π/2], got 2',
    ],
    [
      [{ type: 'point', intensity: 1e300, color: [1e300, 0, 0] }],
      'extensions.KHR_lights_punctual.lights[0].intensity: times the colour overflows the double range',
    ],
  ])('refuses a bad light in one line naming it: %j', async (lights, message) => {
    await expect(
      loadJson(lights, [{ extensions: { KHR_lights_punctual: { light: 0 } } }]),
    ).rejects.toThrow(message);
  });

  it('refuses a node naming a light the file does not have', async () => {
    await expect(
      loadJson([{ type: 'point' }], [{ extensions: { KHR_lights_punctual: { light: 3 } } }]),
    ).rejects.toThrow(
      'nodes[0].extensions.KHR_lights_punctual.light: refers to extensions.KHR_lights_punctual.lights[3], but the file has 1',
    );
  });

  it('ignores, with a warning, a spot whose node is singular (no direction)', async () => {
    const m = await loadJson(
      [{ type: 'spot' }],
      [{ scale: [1, 1, 0], extensions: { KHR_lights_punctual: { light: 0 } } }],
    );
    expect(m.lights).toBeUndefined();
    expect(m.warnings.join('\n')).toContain('nodes[0].extensions.KHR_lights_punctual: ');
  });

  it('a bare model keeps the studio by default, and drops it with environment "none"', async () => {
    const model = await loadGlb(lightsDoc());
    expect(bareModelScene('m.glb', model).environmentMap).not.toBeNull();
    expect(bareModelScene('m.glb', model, { environment: 'none' }).environmentMap).toBeNull();
    // Its lights come with the model's shape and reach the light list.
    const compiled = compileScene(bareModelScene('m.glb', model, { environment: 'none' }));
    expect(Array.from(compiled.data.lightKind)).toEqual([
      LIGHT_SPOT,
      LIGHT_POINT,
      LIGHT_DIRECTIONAL,
    ]);
  });
});

const SCENE = {
  format: 'pathwise-scene/1',
  camera: { position: [0, 1, 3], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
  materials: { white: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
  shapes: [{ type: 'quad', corner: [-1, 0, -1], u: [0, 0, 2], v: [2, 0, 0], material: 'white' }],
};

function withLights(lights: unknown): string {
  return JSON.stringify({ ...SCENE, lights });
}

describe('the scene format’s lights', () => {
  it('reads point, spot and directional lights with their defaults', () => {
    const s = parseScene(
      withLights([
        { type: 'point', position: [0, 2, 0], intensity: 5 },
        {
          type: 'spot',
          position: [0, 2, 0],
          direction: [0, -2, 0],
          intensity: 5,
          color: [1, 0, 0],
        },
        { type: 'directional', direction: [0, 0, -3], intensity: 2, color: [0.5, 0.5, 1] },
      ]),
    );
    expect(s.lights).toEqual([
      {
        type: 'point',
        position: [0, 2, 0],
        direction: [0, 0, -1],
        color: [1, 1, 1],
        intensity: 5,
        innerConeAngle: 0,
        outerConeAngle: 45,
        range: null,
      },
      {
        type: 'spot',
        position: [0, 2, 0],
        direction: [0, -1, 0],
        color: [1, 0, 0],
        intensity: 5,
        innerConeAngle: 0,
        outerConeAngle: 45,
        range: null,
      },
      {
        type: 'directional',
        position: [0, 0, 0],
        direction: [0, 0, -1],
        color: [0.5, 0.5, 1],
        intensity: 2,
        innerConeAngle: 0,
        outerConeAngle: 45,
        range: null,
      },
    ]);
    // None: no key at all, so the scene (and its film key) is what it was before lights.
    expect('lights' in parseScene(JSON.stringify(SCENE))).toBe(false);
  });

  it.each([
    ['not an array', { type: 'point' }, 'lights must be an array, got an object'],
    [
      'a negative intensity',
      [
        { type: 'point', position: [0, 1, 0], intensity: 1 },
        { type: 'point', position: [0, 1, 0], intensity: 1 },
        { type: 'point', position: [0, 1, 0], intensity: -1 },
      ],
      'lights[2].intensity must be >= 0, got -1',
    ],
    [
      'a missing intensity',
      [{ type: 'point', position: [0, 1, 0] }],
      'lights[0].intensity is required but missing (a number)',
    ],
    [
      'a missing position',
      [{ type: 'spot', direction: [0, -1, 0], intensity: 1 }],
      'lights[0].position is required but missing (an array of 3 numbers)',
    ],
    [
      'a zero direction',
      [{ type: 'directional', direction: [0, 0, 0], intensity: 1 }],
      'lights[0].direction must be a non-zero vector of finite length, got [0,0,0]',
    ],
    [
      'an unknown type',
      [{ type: 'area', intensity: 1 }],
      'lights[0].type must be one of "point", "spot", "directional", got "area"',
    ],
    [
      'a key of another type',
      [{ type: 'point', position: [0, 1, 0], intensity: 1, direction: [0, -1, 0] }],
      'lights[0].direction is not a known key',
    ],
    [
      'inner beyond outer',
      [
        {
          type: 'spot',
          position: [0, 1, 0],
          direction: [0, -1, 0],
          intensity: 1,
          innerConeAngle: 40,
          outerConeAngle: 30,
        },
      ],
      'lights[0].innerConeAngle must be at most outerConeAngle (30), got 40',
    ],
    [
      'an outer cone past 90°',
      [
        {
          type: 'spot',
          position: [0, 1, 0],
          direction: [0, -1, 0],
          intensity: 1,
          outerConeAngle: 120,
        },
      ],
      'lights[0].outerConeAngle must be in (0, 90] degrees, got 120',
    ],
    [
      'an intensity over the bound',
      [{ type: 'point', position: [0, 1, 0], intensity: 1e13 }],
      'lights[0].intensity × color must be at most 1e12 in every channel, got 10000000000000 × [1,1,1]',
    ],
  ])('refuses %s in one message naming the entry', (_, lights, message) => {
    let error: unknown;
    try {
      parseScene(withLights(lights));
    } catch (e) {
      error = e;
    }
    expect(error).toBeInstanceOf(SceneError);
    expect((error as SceneError).problems[0]).toBe(message);
  });
});

describe('compiled punctual lights', () => {
  const light = (over: Partial<LightDesc>): LightDesc => ({
    type: 'point',
    position: [0, 0, 0],
    direction: [0, 0, -1],
    color: [1, 1, 1],
    intensity: 1,
    innerConeAngle: 0,
    outerConeAngle: 45,
    range: null,
    ...over,
  });

  it('weighs the lights by power / π: point 4I, spot 2(1 − cos outer)I, directional E R²; black ones are dropped', () => {
    const c = compilePunctualLights(
      [
        light({ intensity: 2 }),
        light({ type: 'spot', intensity: 3, outerConeAngle: 60 }),
        light({ type: 'directional', intensity: 5 }),
        light({ intensity: 0 }),
        light({ color: [0, 0, 0] }),
      ],
      10,
    );
    expect(c.kinds).toEqual([LIGHT_POINT, LIGHT_SPOT, LIGHT_DIRECTIONAL]);
    close(c.power, [8, 3, 500], 1e-12);
    close(c.powerLog, c.power.map(Math.log2), 1e-12);
  });

  it('a scene without lights compiles no punctual record and no light list', () => {
    const c = compileScene(parseScene(JSON.stringify(SCENE)));
    expect(c.data.punctual.length).toBe(0);
    expect(c.lights).toBeNull();
  });

  it('samplePunctual: the inverse square, the cone, the range, and nothing at the light itself', () => {
    const data = compilePunctualLights(
      [
        light({ position: [0, 2, 0], intensity: 8, range: 3 }),
        light({
          type: 'spot',
          position: [0, 2, 0],
          direction: [0, -1, 0],
          intensity: 8,
          innerConeAngle: 10,
          outerConeAngle: 30,
        }),
        light({ type: 'directional', direction: [0, -1, 0], intensity: 3 }),
      ],
      1,
    ).data;
    const s = new LightSample();
    const at = (x: number, y: number, z: number) => {
      s.refX = x;
      s.refY = y;
      s.refZ = z;
      return s;
    };
    expect(samplePunctual(data, 0, LIGHT_POINT, 0.25, at(0, 0, 0))).toBe(true);
    close([s.wx, s.wy, s.wz, s.distance, s.r, s.pdf], [0, 1, 0, 2, 2, 0.25]);
    close([s.px, s.py, s.pz], [0, 2, 0]);
    // 3.2 away: beyond the range of 3.
    expect(samplePunctual(data, 0, LIGHT_POINT, 0.25, at(0, -1.2, 0))).toBe(false);
    expect(samplePunctual(data, 0, LIGHT_POINT, 0.25, at(0, 2, 0))).toBe(false);
    // The spot: full inside 10°, the reference falloff between, nothing past 30°.
    const scale = spotAngleScale(Math.cos(Math.PI / 18), Math.cos(Math.PI / 6));
    for (const deg of [0, 5, 15, 25, 29]) {
      const t = Math.tan((deg * Math.PI) / 180) * 2;
      expect(samplePunctual(data, 1, LIGHT_SPOT, 1, at(t, 0, 0))).toBe(true);
      const d2 = 4 + t * t;
      const expected =
        (8 / d2) * spotAttenuation(Math.cos((deg * Math.PI) / 180), Math.cos(Math.PI / 6), scale);
      close([s.r], [expected], 1e-12 * expected + 1e-15);
    }
    expect(
      samplePunctual(data, 1, LIGHT_SPOT, 1, at(Math.tan((31 * Math.PI) / 180) * 2, 0, 0)),
    ).toBe(false);
    expect(samplePunctual(data, 2, LIGHT_DIRECTIONAL, 0.5, at(5, 5, 5))).toBe(true);
    close([s.wx, s.wy, s.wz, s.r, s.pdf], [0, 1, 0, 3, 0.5]);
    expect(s.distance).toBe(Infinity);
  });

  it('spotAttenuation is the reference formula: 1 inside, 0 outside, t² between', () => {
    const co = Math.cos(0.5);
    const ci = Math.cos(0.2);
    const s = spotAngleScale(ci, co);
    expect(spotAttenuation(1, co, s)).toBe(1);
    expect(spotAttenuation(Math.cos(0.6), co, s)).toBe(0);
    const mid = Math.cos(0.35);
    close([spotAttenuation(mid, co, s)], [((mid - co) / (ci - co)) ** 2]);
    // The spec's floor: cones closer than 0.001 in cosine use scale 1000.
    expect(spotAngleScale(0.9999, 0.9995)).toBe(1000);
  });
});
