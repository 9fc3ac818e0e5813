/**
 * Loader and validator of the scene format `pathwise-scene/1` (docs: scene-format.md).
 *
 * A file that breaks any rule is rejected as a whole, never silently repaired: every problem
 * found in one pass is collected, each naming its JSON path and the offending value, and a
 * single SceneError carries them all. A valid file yields a fresh Scene with every optional
 * key filled with its documented default, so no consumer re-derives a default.
 */

import {
  DEFAULT_SETTINGS,
  LIMITS,
  type MaterialDesc,
  type Scene,
  type SettingsDesc,
  type ShapeDesc,
  type SphereDesc,
  type Vec3,
} from '../format/types.ts';
import {
  POSITIVE,
  UNIT_INTERVAL,
  childPath,
  closest,
  describe,
  describeType,
  expectInteger,
  expectKnownKeys,
  expectNumber,
  expectObject,
  expectOneOf,
  expectString,
  expectVec3,
  formatVec,
  indexPath,
  length,
  plainVec3,
  type Problems,
} from './validate-helpers.ts';
import { decodeUtf8, Utf8Error, utf8Length } from '../../io/utf8.ts';
import { JsonError, parseJson } from '../../io/json.ts';
import { RADIANCE } from './radiance.ts';
import { Q_NORMAL, QUAD_STRIDE, writeQuadRecord } from '../../geometry/shapes.ts';
import { checkCamera } from './camera-desc.ts';
import { checkEnvironment } from './environment-desc.ts';
import { GLTF_KEYS, checkGltfShape } from './gltf-desc.ts';
import { MESH_KEYS, checkMesh } from './mesh-desc.ts';
import { sceneRangeProblem } from './extent.ts';
import { checkLights } from './light-desc.ts';

const FORMAT = 'pathwise-scene/1';

export class SceneError extends Error {
  /** Every violation found, each a sentence that starts with the offending JSON path. */
  readonly problems: string[];

  constructor(problems: string[]) {
    const more = problems.length - 1;
    const suffix = more > 0 ? ` (and ${more} more problem${more === 1 ? '' : 's'})` : '';
    super((problems[0] ?? 'invalid scene') + suffix);
    this.name = 'SceneError';
    this.problems = problems;
  }
}

/**
 * The problem of a scene file over the size limit. `size` is its size in bytes when known
 * (a regular file, a File, the bytes in hand); when reading stopped at the limit (a pipe or
 * a device reports no size), `exact` is false and `size` is what was read.
 */
export function sceneSizeProblem(size: number, exact = true): string {
  const got = exact ? `${size}` : `at least ${size}`;
  return `scene file must be at most ${LIMITS.fileBytes} bytes (16 MiB), got ${got} bytes`;
}

/**
 * Parses and validates a scene file: its bytes (checked to be at most 16 MiB and strict
 * UTF-8; a leading byte-order mark is dropped) or its text. Throws SceneError, whose
 * message is one printable line.
 */
export function parseScene(input: string | Uint8Array): Scene {
  let text: string;
  if (typeof input === 'string') {
    const bytes = utf8Length(input, LIMITS.fileBytes);
    if (bytes > LIMITS.fileBytes) {
      throw new SceneError([
        bytes === Infinity ? sceneSizeProblem(input.length, false) : sceneSizeProblem(bytes),
      ]);
    }
    // A leading byte-order mark is an artefact of the text encoding, not of the scene.
    text = input.charCodeAt(0) === 0xfeff ? input.slice(1) : input;
  } else {
    if (input.length > LIMITS.fileBytes) throw new SceneError([sceneSizeProblem(input.length)]);
    try {
      text = decodeUtf8(input);
    } catch (e) {
      if (e instanceof Utf8Error) throw new SceneError([`scene file is ${e.message}`]);
      throw e;
    }
  }
  let value: unknown;
  try {
    value = parseJson(text);
  } catch (e) {
    if (!(e instanceof JsonError)) throw e;
    throw new SceneError([
      e.kind === 'duplicate'
        ? `${e.message}: a key may appear only once`
        : `scene file is not valid JSON: ${e.message}`,
    ]);
  }
  return validateScene(value);
}

const TOP_KEYS = [
  'format',
  'name',
  'camera',
  'settings',
  'materials',
  'shapes',
  'environment',
  'lights',
];

/** Validates a parsed scene (or any JS value) and returns a fresh Scene with defaults filled. */
export function validateScene(value: unknown): Scene {
  const problems: Problems = [];
  const root = expectObject(value, 'scene', problems);
  if (root === undefined) throw new SceneError(problems);

  // The format comes first: if it is wrong, that is the problem to lead with.
  expectOneOf(root.format, 'format', [FORMAT], problems);
  expectKnownKeys(root, '', TOP_KEYS, problems);

  const name = root.name === undefined ? '' : expectString(root.name, 'name', problems);
  const camera = checkCamera(root.camera, problems);
  const settings = checkSceneSettings(root.settings, problems);
  const materials = checkMaterials(root.materials, problems);
  const shapes = checkShapes(root.shapes, materials, problems);
  const environment = checkEnvironment(root.environment, problems);
  const lights = checkLights(root.lights, problems);

  if (problems.length > 0) throw new SceneError(problems);
  // No problem was recorded, so every part validated and is defined.
  const scene: Scene = {
    format: FORMAT,
    name: name!,
    camera: camera!,
    settings: settings!,
    materials: Object.fromEntries(materials!),
    shapes: shapes!,
    environment: environment!.constant,
    environmentMap: environment!.map,
    // Only when there are some: a scene without lights stays the object (and the film
    // key, cli/film-file.ts) it was before lights existed.
    ...(lights!.length > 0 ? { lights } : {}),
  };
  const range = sceneRangeProblem(scene);
  if (range !== undefined) throw new SceneError([range]);
  return markValidated(scene);
}

/**
 * Scenes this loader made (validateScene, resolveSceneFiles), which may be handed back
 * as they are: a loaded scene holds decoded meshes and maps, not the JSON it came from.
 */
const validated = new WeakSet<object>();

export function markValidated(scene: Scene): Scene {
  validated.add(scene);
  return scene;
}

/** Whether `value` is a scene this loader made (in this thread). */
export function isValidatedScene(value: unknown): value is Scene {
  return typeof value === 'object' && value !== null && validated.has(value);
}

const SETTING_KEYS = ['width', 'height', 'maxBounces', 'spp'] as const;
type SettingKey = (typeof SETTING_KEYS)[number];

function checkSceneSettings(value: unknown, problems: Problems): SettingsDesc | undefined {
  if (value === undefined) return { ...DEFAULT_SETTINGS };
  const obj = expectObject(value, 'settings', problems);
  if (obj === undefined) return undefined;
  expectKnownKeys(obj, 'settings', SETTING_KEYS, problems);
  const merged = { ...DEFAULT_SETTINGS };
  for (const key of SETTING_KEYS) if (obj[key] !== undefined) merged[key] = obj[key] as number;
  return checkSettings(merged, (key) => `settings.${key}`, problems);
}

/** The rules of settings, shared by scene files and command-line overrides. */
function checkSettings(
  s: Record<SettingKey, unknown>,
  label: (key: SettingKey) => string,
  problems: Problems,
): SettingsDesc | undefined {
  const before = problems.length;
  const width = checkDimension(s.width, label('width'), problems);
  const height = checkDimension(s.height, label('height'), problems);
  const maxBounces = expectInteger(
    s.maxBounces,
    label('maxBounces'),
    problems,
    0,
    LIMITS.maxBounces,
  );
  const spp = expectInteger(s.spp, label('spp'), problems, 1, LIMITS.spp);
  if (width !== undefined && height !== undefined && width * height > LIMITS.pixels) {
    problems.push(
      `${label('width')} * ${label('height')} must be at most ${LIMITS.pixels} pixels, ` +
        `got ${width} * ${height} = ${width * height}`,
    );
  }
  if (problems.length > before) return undefined;
  return { width: width!, height: height!, maxBounces: maxBounces!, spp: spp! };
}

function checkDimension(value: unknown, path: string, problems: Problems): number | undefined {
  return expectInteger(value, path, problems, 1, Infinity);
}

/** How option names appear in messages: a prefix (default `--`) or a function of the key. */
export type SettingLabel = string | ((key: keyof SettingsDesc) => string);

/**
 * Applies command-line overrides to validated settings under the same rules and limits,
 * e.g. `--spp must be an integer in [1, 1048576], got 0`. Keys that are undefined in
 * `override` keep their base value. Throws SceneError.
 */
export function validateSettingsOverride(
  base: SettingsDesc,
  override: Partial<SettingsDesc>,
  where: SettingLabel = '--',
): SettingsDesc {
  const label = typeof where === 'string' ? (key: SettingKey) => where + key : where;
  const problems: Problems = [];
  const merged: Record<SettingKey, unknown> = { ...base };
  for (const [key, value] of Object.entries(override)) {
    if (value === undefined) continue;
    if ((SETTING_KEYS as readonly string[]).includes(key)) merged[key as SettingKey] = value;
    else problems.push(`${typeof where === 'string' ? where + key : key} is not a known setting`);
  }
  const settings = checkSettings(merged, label, problems);
  if (problems.length > 0 || settings === undefined) throw new SceneError(problems);
  return settings;
}

const MATERIAL_TYPES = ['diffuse', 'conductor', 'dielectric'] as const;
const MATERIAL_KEYS: Record<MaterialDesc['type'], string[]> = {
  diffuse: ['type', 'albedo', 'emission'],
  conductor: ['type', 'color', 'roughness', 'emission'],
  dielectric: ['type', 'ior', 'color', 'roughness', 'emission'],
};

/**
 * Returns the materials as entries (so that a material named `__proto__` stays an own key
 * when the caller builds the record with Object.fromEntries). The names are returned even
 * when a material is invalid, so that shapes are only blamed for names that do not exist.
 */
function checkMaterials(value: unknown, problems: Problems): Map<string, MaterialDesc> | undefined {
  const obj = expectObject(value, 'materials', problems);
  if (obj === undefined) return undefined;
  const out = new Map<string, MaterialDesc>();
  for (const name of Object.keys(obj)) {
    const material = checkMaterial(obj[name], childPath('materials', name), problems);
    // Placeholder for an invalid material: the scene is rejected anyway, but the name exists.
    out.set(name, material ?? ({} as MaterialDesc));
  }
  return out;
}

function checkMaterial(value: unknown, path: string, problems: Problems): MaterialDesc | undefined {
  const obj = expectObject(value, path, problems);
  if (obj === undefined) return undefined;
  const type = expectOneOf(obj.type, childPath(path, 'type'), MATERIAL_TYPES, problems);
  if (type === undefined) return undefined; // the allowed keys depend on the type
  const before = problems.length;
  expectKnownKeys(obj, path, MATERIAL_KEYS[type], problems);
  const at = (key: string) => childPath(path, key);
  const emission =
    obj.emission === undefined
      ? ([0, 0, 0] as Vec3)
      : expectVec3(obj.emission, at('emission'), problems, RADIANCE);

  let material: MaterialDesc | undefined;
  if (type === 'diffuse') {
    const albedo = expectVec3(obj.albedo, at('albedo'), problems, UNIT_INTERVAL);
    material = { type, albedo: albedo!, emission: emission! };
  } else if (type === 'conductor') {
    const color = expectVec3(obj.color, at('color'), problems, UNIT_INTERVAL);
    const roughness = expectNumber(obj.roughness, at('roughness'), problems, UNIT_INTERVAL);
    material = { type, color: color!, roughness: roughness!, emission: emission! };
  } else {
    const ior = expectNumber(obj.ior, at('ior'), problems, POSITIVE);
    const color =
      obj.color === undefined
        ? ([1, 1, 1] as Vec3)
        : expectVec3(obj.color, at('color'), problems, UNIT_INTERVAL);
    const roughness =
      obj.roughness === undefined
        ? 0
        : expectNumber(obj.roughness, at('roughness'), problems, UNIT_INTERVAL);
    // The spec makes rough glass optional; this renderer lacks it, so it must say so.
    if (roughness !== undefined && roughness > 0) {
      problems.push(
        `${at('roughness')}: rough dielectric (roughness > 0) is not supported by pathwise; ` +
          `use roughness 0, got ${roughness}`,
      );
    }
    material = { type, ior: ior!, color: color!, roughness: roughness!, emission: emission! };
  }
  return problems.length > before ? undefined : material;
}

const SHAPE_TYPES = ['sphere', 'quad', 'mesh', 'gltf'] as const;
const SHAPE_KEYS: Record<ShapeDesc['type'], string[]> = {
  sphere: ['type', 'center', 'radius', 'material'],
  quad: ['type', 'corner', 'u', 'v', 'material'],
  mesh: MESH_KEYS,
  gltf: GLTF_KEYS,
};

function checkShapes(
  value: unknown,
  materials: Map<string, MaterialDesc> | undefined,
  problems: Problems,
): ShapeDesc[] | undefined {
  if (value === undefined) {
    problems.push('shapes is required but missing (an array)');
    return undefined;
  }
  if (!Array.isArray(value)) {
    problems.push(`shapes must be an array, got ${describeType(value)}`);
    return undefined;
  }
  // The limit bounds the work of loading and building the scene, so past it the shapes
  // themselves are not examined: the scene is rejected on the count alone.
  if (value.length > LIMITS.shapes) {
    problems.push(`shapes has ${value.length} entries, more than the limit of ${LIMITS.shapes}`);
    return undefined;
  }
  const before = problems.length;
  const known = materials === undefined ? undefined : new MaterialNames(materials);
  const out = value.map(
    (shape, i) =>
      plainSphere(shape, known) ?? checkShape(shape, indexPath('shapes', i), known, problems),
  );
  if (problems.length > before) return undefined;
  // Inline meshes count against the scene's triangle limit here; mesh files when read.
  let triangles = 0;
  for (const shape of out) {
    if (shape?.type === 'mesh' && shape.data !== null) {
      triangles += shape.data.indices.length / 3 + shape.data.skipped;
    }
  }
  if (triangles > LIMITS.triangles) {
    problems.push(
      `shapes hold ${triangles} triangles, more than the limit of ${LIMITS.triangles} per scene`,
    );
    return undefined;
  }
  return out as ShapeDesc[];
}

/**
 * A sphere with nothing to report, accepted without building its paths (a scene may have
 * 10,000 of them); undefined sends the shape the long way (checkShape), which accepts
 * the same spheres and names every problem of the others.
 */
function plainSphere(value: unknown, materials: MaterialNames | undefined): SphereDesc | undefined {
  if (typeof value !== 'object' || value === null || Array.isArray(value)) return undefined;
  const obj = value as Record<string, unknown>;
  if (obj.type !== 'sphere' || materials === undefined) return undefined;
  const known = SHAPE_KEYS.sphere;
  for (const key of Object.keys(obj)) if (!known.includes(key)) return undefined;
  const { material, radius } = obj;
  if (typeof material !== 'string' || !materials.has(material)) return undefined;
  if (typeof radius !== 'number' || !Number.isFinite(radius) || !POSITIVE.ok(radius)) {
    return undefined;
  }
  const center = plainVec3(obj.center);
  if (center === undefined) return undefined;
  return { type: 'sphere', center, radius, material };
}

function checkShape(
  value: unknown,
  path: string,
  materials: MaterialNames | undefined,
  problems: Problems,
): ShapeDesc | undefined {
  const obj = expectObject(value, path, problems);
  if (obj === undefined) return undefined;
  const type = expectOneOf(obj.type, `${path}.type`, SHAPE_TYPES, problems);
  if (type === undefined) return undefined; // the allowed keys depend on the type
  expectKnownKeys(obj, path, SHAPE_KEYS[type], problems);
  // A glTF model brings its own materials.
  if (type === 'gltf') return checkGltfShape(obj, path, problems);
  const material = checkMaterialRef(obj.material, `${path}.material`, materials, problems);
  if (type === 'mesh') return checkMesh(obj, path, material, problems);
  if (type === 'sphere') {
    const center = expectVec3(obj.center, `${path}.center`, problems);
    const radius = expectNumber(obj.radius, `${path}.radius`, problems, POSITIVE);
    return { type, center: center!, radius: radius!, material: material! };
  }
  const corner = expectVec3(obj.corner, `${path}.corner`, problems);
  const u = expectVec3(obj.u, `${path}.u`, problems);
  const v = expectVec3(obj.v, `${path}.v`, problems);
  if (corner !== undefined && u !== undefined && v !== undefined) {
    checkQuadGeometry(corner, u, v, path, problems);
  }
  return { type, corner: corner!, u: u!, v: v!, material: material! };
}

const quadScratch = new Float64Array(QUAD_STRIDE);

/**
 * A quad must span a non-zero, finite area in double precision, with a finite unit normal
 * (docs/scene-format.md, "Bad input"). The record the renderer will use is built here with
 * the same code (writeQuadRecord), so what passes here is exactly what renders: no quad can
 * bring a NaN normal or an infinite axis into the tracer.
 */
function checkQuadGeometry(corner: Vec3, u: Vec3, v: Vec3, path: string, problems: Problems): void {
  const area = writeQuadRecord(corner, u, v, quadScratch, 0);
  const edges = `got u ${formatVec(u)} and v ${formatVec(v)}`;
  const n: Vec3 = [quadScratch[Q_NORMAL], quadScratch[Q_NORMAL + 1], quadScratch[Q_NORMAL + 2]];
  if (!(length(n) > 0.5)) {
    // NaN normal: the scaled cross product is zero.
    problems.push(`${path} is a degenerate quad: u and v are parallel or zero (area 0), ${edges}`);
  } else if (area === 0) {
    problems.push(
      `${path} is a degenerate quad: its area |u x v| underflows to 0 in double precision, ${edges}`,
    );
  } else if (!Number.isFinite(area)) {
    problems.push(`${path} is too large: its area |u x v| overflows double precision, ${edges}`);
  } else if (!quadScratch.every(Number.isFinite)) {
    problems.push(
      `${path} cannot be intersected in double precision (an edge is too short or the ` +
        `corner too far for its size), got corner ${formatVec(corner)}, u ${formatVec(u)} ` +
        `and v ${formatVec(v)}`,
    );
  }
}

/**
 * The material names, with "did you mean" suggestions. A suggestion compares the unknown
 * name with every material (O(length) each, see `closest`), so 10,000 shapes naming 10,000
 * different missing materials among 10,000 would still cost 10^8 comparisons: suggestions
 * are memoized per name and stop once SUGGESTION_BUDGET comparisons are spent (only the
 * first problems are ever read; every one is still reported).
 */
const SUGGESTION_BUDGET = 200_000;

class MaterialNames {
  private readonly materials: Map<string, MaterialDesc>;
  private readonly suggestions = new Map<string, string | undefined>();
  private spent = 0;

  constructor(materials: Map<string, MaterialDesc>) {
    this.materials = materials;
  }

  has(name: string): boolean {
    return this.materials.has(name);
  }

  suggest(name: string): string | undefined {
    if (this.suggestions.has(name)) return this.suggestions.get(name);
    if (this.spent + this.materials.size > SUGGESTION_BUDGET) return undefined;
    this.spent += this.materials.size;
    const guess = closest(name, this.materials.keys());
    this.suggestions.set(name, guess);
    return guess;
  }
}

function checkMaterialRef(
  value: unknown,
  path: string,
  materials: MaterialNames | undefined,
  problems: Problems,
): string | undefined {
  const name = expectString(value, path, problems);
  // If `materials` itself is broken, that is reported once there, not again per shape.
  if (name === undefined || materials === undefined || materials.has(name)) return name;
  const guess = materials.suggest(name);
  const hint = guess === undefined ? '' : ` (did you mean ${describe(guess)}?)`;
  problems.push(`${path} names unknown material ${describe(name)}${hint}`);
  return undefined;
}
