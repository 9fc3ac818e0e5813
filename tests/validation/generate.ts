/**
 * Random valid `pathwise-scene/1` scenes, deterministic by seed: the same
 * seed gives the same JSON on every machine (the stream is the project's
 * PCG hash; see rng.ts). An archetype (archetypes.ts) builds the scene in
 * its unit frame; the whole scene is then mapped by a random similarity:
 * scale 1e-4…1e4 (log-uniform, a fifth of scenes exactly at either end),
 * a random rotation for 60 % of scenes, and a translation of up to 50×
 * the scene's size. Every scene goes through parseScene, so an invalid
 * one throws here rather than in a test.
 *
 * Use: `generateScene(seed)`; `node scripts/run-ts.mjs
 * tests/validation/export-scenes.ts` writes the reference set as files.
 */
import { parseScene, type Scene } from '../../src/core/index.ts';
import { ARCHETYPES } from './archetypes.ts';
import { SceneBuilder, type Feature, type SceneJson, type ShapeJson } from './builder.ts';
import { Rng } from './rng.ts';
import { Similarity, normalize, type Vec3 } from './vec.ts';

export interface GeneratedScene {
  seed: number;
  archetype: string;
  /** The file as written: what Mitsuba and the CLI read. */
  json: SceneJson;
  /** The same after parseScene (defaults filled). */
  scene: Scene;
  features: Feature[];
  /** The similarity's scale factor. */
  scale: number;
}

export interface GenerateOptions {
  /** Image size written into settings (tests override it anyway). */
  width?: number;
  height?: number;
  /** Restrict to one archetype by name. */
  archetype?: string;
}

export function generateScene(seed: number, options: GenerateOptions = {}): GeneratedScene {
  const rng = new Rng(seed);
  const b = new SceneBuilder(rng);
  const candidates = options.archetype
    ? ARCHETYPES.filter((a) => a.name === options.archetype)
    : ARCHETYPES;
  if (candidates.length === 0) throw new Error(`unknown archetype ${options.archetype}`);
  const archetype = rng.weighted(candidates.map((a) => [a, a.weight] as const));
  const staged = archetype.build(b);

  const scale = rng.weighted([
    [1e-4, 0.1],
    [1e4, 0.1],
    [rng.logUniform(1e-4, 1e4), 0.6],
    [1, 0.2],
  ] as const);
  if (scale <= 1e-4) b.tag('scale-1e-4');
  if (scale >= 1e4) b.tag('scale-1e4');
  const rotated = rng.chance(0.6);
  if (rotated) b.tag('rotated');
  const sim = new Similarity(
    scale,
    rng.direction(),
    rotated ? rng.uniform(0, 2 * Math.PI) : 0,
    rng.direction().map((x) => x * scale * rng.uniform(0, 50)) as Vec3,
  );

  const cam = staged.camera;
  const json: SceneJson = {
    format: 'pathwise-scene/1',
    name: `generated ${seed} (${archetype.name})`,
    camera: {
      position: sim.point(cam.position),
      target: sim.point(cam.target),
      up: normalize(sim.direction(cam.up)),
      fovY: cam.fovY,
      ...(cam.aperture !== undefined
        ? { aperture: cam.aperture * scale, focusDistance: cam.focusDistance! * scale }
        : {}),
    },
    settings: {
      width: options.width ?? 32,
      height: options.height ?? 24,
      maxBounces: staged.maxBounces,
      spp: 64,
    },
    materials: b.materials,
    shapes: b.shapes.map((s) => transformShape(s, sim)),
    ...(b.environment !== null ? { environment: b.environment } : {}),
  };
  const scene = parseScene(JSON.stringify(json));
  return {
    seed,
    archetype: archetype.name,
    json,
    scene,
    features: [...b.features].sort(),
    scale,
  };
}

/** Maps one shape by the similarity; a new shape kind adds its case here. */
function transformShape(s: ShapeJson, sim: Similarity): ShapeJson {
  switch (s.type) {
    case 'sphere':
      return { ...s, center: sim.point(s.center), radius: s.radius * sim.scale };
    case 'quad':
      return { ...s, corner: sim.point(s.corner), u: sim.vector(s.u), v: sim.vector(s.v) };
  }
}
