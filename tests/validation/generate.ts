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
 * Two families: 'classic' (archetypes.ts: spheres, quads, constant
 * environments; the default, whose scenes never change for a seed) and 'mesh'
 * (archetypes-mesh.ts: triangle meshes, emissive meshes and environment maps).
 * A mesh-family scene may name files (OBJ / PLY meshes, an .hdr / .pfm map):
 * their bytes come in `files`, and `scene` has them read and decoded already,
 * by the core's own decoders.
 *
 * The 'gltf' family (archetypes-gltf.ts) writes glTF models as `.glb` files in
 * `files`; loading them is asynchronous, so its `scene` keeps them unread until
 * `loadGltfModels` reads them through the core's loader. The 'punctual' family
 * (archetypes-punctual.ts) is glTF models under KHR_lights_punctual-style lights
 * (the scene's `lights`), with no Dirac lobe anywhere. The 'many' family
 * (archetypes-many.ts) is rooms lit by tens to hundreds of small emitters.
 *
 * Use: `generateScene(seed)`; `node scripts/run-ts.mjs
 * tests/validation/export-references.ts` writes the reference set as files.
 */
import { BVH_THRESHOLD, parseScene, type MeshDesc, type Scene } from '../../src/core/index.ts';
import { buildMeshData } from '../../src/core/geometry/mesh-data.ts';
import { parseObj } from '../../src/core/io/obj.ts';
import { parsePly } from '../../src/core/io/ply.ts';
import { decodeEnvironmentImage, resolveSceneFiles } from '../../src/core/scene/load/load.ts';
import { compose, similarityMatrix, transformPositions } from './affine.ts';
import { ARCHETYPES } from './archetypes.ts';
import { MESH_ARCHETYPES } from './archetypes-mesh.ts';
import { GLTF_ARCHETYPES } from './archetypes-gltf.ts';
import { PUNCTUAL_ARCHETYPES } from './archetypes-punctual.ts';
import { MANY_ARCHETYPES } from './archetypes-many.ts';
import { encodeGlb } from './gltf-files.ts';
import {
  SceneBuilder,
  type Feature,
  type MeshJson,
  type MeshStorage,
  type PunctualLightJson,
  type SceneJson,
  type ShapeJson,
} from './builder.ts';
import { encodeMeshFile } from './mesh-files.ts';
import { Rng } from './rng.ts';
import { Similarity, normalize, type Vec3 } from './vec.ts';

export type Family = 'classic' | 'mesh' | 'gltf' | 'punctual' | 'many';

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
  /** Files the scene names, by their path relative to it (mesh family only). */
  files: Record<string, Uint8Array>;
}

export interface GenerateOptions {
  /** Image size written into settings (tests override it anyway). */
  width?: number;
  height?: number;
  /** Restrict to one archetype by name. */
  archetype?: string;
  /** Which family of archetypes (default 'classic'). */
  family?: Family;
  /** Prefix of the names of the files a scene names (default `s<seed>`). */
  filePrefix?: string;
}

export function generateScene(seed: number, options: GenerateOptions = {}): GeneratedScene {
  const rng = new Rng(seed);
  const b = new SceneBuilder(rng);
  const family = options.family ?? 'classic';
  const all =
    family === 'mesh'
      ? MESH_ARCHETYPES
      : family === 'gltf'
        ? GLTF_ARCHETYPES
        : family === 'punctual'
          ? PUNCTUAL_ARCHETYPES
          : family === 'many'
            ? MANY_ARCHETYPES
            : ARCHETYPES;
  const candidates = options.archetype ? all.filter((a) => a.name === options.archetype) : all;
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
  const prefix = options.filePrefix ?? `s${seed}`;
  const files: Record<string, Uint8Array> = {};
  const shapes = b.shapes.map((s, i) => {
    const t = transformShape(s, sim);
    const model = b.gltfObjects.get(i);
    if (t.type === 'gltf' && model !== undefined) {
      const file = `${prefix}-${i}.glb`;
      files[file] = encodeGlb(model.mesh, model.material);
      return { ...t, file };
    }
    const storage = b.meshStorage.get(i);
    return t.type === 'mesh' && storage && storage !== 'inline'
      ? meshFile(t, storage, `${prefix}-${i}`, files)
      : t;
  });
  let environment: SceneJson['environment'];
  const env = b.environment;
  if (Array.isArray(env)) environment = env;
  else if (env !== null) {
    const file = `${prefix}-env.${env.format}`;
    files[file] = env.bytes;
    environment = {
      type: 'map',
      file,
      ...(env.scale !== 1 ? { scale: env.scale } : {}),
      ...(env.rotationY !== 0 ? { rotationY: env.rotationY } : {}),
    };
  }
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
    shapes,
    ...(environment !== undefined ? { environment } : {}),
    ...(b.punctualLights.length > 0
      ? { lights: b.punctualLights.map((l) => transformLight(l, sim)) }
      : {}),
  };
  const scene = readFiles(parseScene(JSON.stringify(json)), files);
  const triangles = scene.shapes.reduce(
    (n, s) => n + (s.type === 'mesh' ? s.data!.indices.length / 3 : 1),
    0,
  );
  if (triangles >= BVH_THRESHOLD) b.tag('bvh');
  return {
    seed,
    archetype: archetype.name,
    json,
    scene,
    features: [...b.features].sort(),
    scale,
    files,
  };
}

/**
 * The scene with the files it names read from `files` and decoded, as
 * resolveSceneFiles (src/core/scene/load/load.ts) does through a reader, but at once.
 */
function readFiles(scene: Scene, files: Record<string, Uint8Array>): Scene {
  const limits = { maxTriangles: 10_000_000, sceneTriangles: 10_000_000 };
  const shapes = scene.shapes.map((s): typeof s => {
    if (s.type !== 'mesh' || s.data !== null) return s;
    const bytes = files[s.file!];
    const raw = s.file!.endsWith('.obj') ? parseObj(bytes, limits) : parsePly(bytes, limits);
    return { ...s, data: buildMeshData(raw, s.transform) } satisfies MeshDesc;
  });
  const map = scene.environmentMap ?? null;
  const environmentMap =
    map === null ? null : { ...map, image: decodeEnvironmentImage(files[map.file], map, 'map') };
  return { ...scene, shapes, environmentMap };
}

/** A mesh written to a file beside the scene; the JSON keeps its material and transform. */
function meshFile(
  m: MeshJson,
  storage: Exclude<MeshStorage, 'inline'>,
  name: string,
  files: Record<string, Uint8Array>,
): MeshJson {
  const file = `${name}.${storage === 'obj' ? 'obj' : 'ply'}`;
  files[file] = encodeMeshFile(
    {
      positions: m.positions!,
      indices: m.indices ?? m.positions!.map((_, i) => i).slice(0, m.positions!.length / 3),
      normals: m.normals,
    },
    storage,
  );
  return {
    type: 'mesh',
    material: m.material,
    file,
    ...(m.transform ? { transform: m.transform } : {}),
  };
}

/**
 * Maps a punctual light by the similarity: position and direction as points and
 * directions; a point or spot light's intensity (candela) by scale², so the irradiance
 * I/d² it gives at the mapped distances, and with it the image, stays the same.
 */
function transformLight(l: PunctualLightJson, sim: Similarity): PunctualLightJson {
  return {
    ...l,
    ...(l.position ? { position: sim.point(l.position) } : {}),
    ...(l.direction ? { direction: normalize(sim.direction(l.direction)) } : {}),
    intensity: l.type === 'directional' ? l.intensity : l.intensity * sim.scale * sim.scale,
  };
}

/** Maps one shape by the similarity; a new shape kind adds its case here. */
function transformShape(s: ShapeJson, sim: Similarity): ShapeJson {
  switch (s.type) {
    case 'sphere':
      return { ...s, center: sim.point(s.center), radius: s.radius * sim.scale };
    case 'quad':
      return { ...s, corner: sim.point(s.corner), u: sim.vector(s.u), v: sim.vector(s.v) };
    case 'gltf':
      return { ...s, transform: compose(similarityMatrix(sim), s.transform!) };
    case 'mesh': {
      // A transform takes the similarity on the left; positions without one are mapped
      // (and their normals rotated: a similarity keeps unit normals unit).
      const S = similarityMatrix(sim);
      if (s.transform) return { ...s, transform: compose(S, s.transform) };
      const out: MeshJson = { ...s, positions: transformPositions(S, s.positions!) };
      if (s.normals) {
        const n: number[] = [];
        for (let i = 0; i < s.normals.length; i += 3) {
          n.push(...normalize(sim.direction([s.normals[i], s.normals[i + 1], s.normals[i + 2]])));
        }
        out.normals = n;
      }
      return out;
    }
  }
}

/**
 * The glTF family's scene with its models loaded by the core's own glTF loader
 * (resolveSceneFiles, reading `files`), as the CLI would load the scene.
 */
export async function loadGltfModels(g: GeneratedScene): Promise<Scene> {
  const reader = {
    async read(path: string): Promise<Uint8Array> {
      const bytes = g.files[path];
      if (bytes === undefined) throw new Error(`no such generated file ${path}`);
      return bytes;
    },
  };
  return resolveSceneFiles(g.scene, reader);
}
