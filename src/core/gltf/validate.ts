/**
 * Structural checks of a glTF 2.0 JSON document before glTF-Transform reads
 * it: every index in range, every accessor inside its buffer view and every
 * view inside its buffer, aligned; the node graph a forest; the triangles
 * the default scene instances counted against the limit. glTF-Transform
 * (like most loaders) trusts these and fails deep inside with a RangeError,
 * or allocates what a lying count asks for; here each gets one message
 * naming its place in the file (glTF 2.0 §3.6 "Binary data storage", §5
 * "Properties reference").
 *
 * The checks by concern: validate-values.ts (JSON types, indices, ranges),
 * validate-attributes.ts (what each attribute semantic allows, one count per
 * primitive, shared vertex views), validate-materials.ts, validate-features.ts
 * (skins, animations, samplers, cameras, morph weights: read or not, they
 * must be well formed); once the buffers are read, validate-buffers.ts (byte
 * ranges) and validate-sparse.ts; after the node transforms,
 * validate-world.ts (world space finite and not collapsed).
 */
import { quote } from '../util/message.ts';
import { checkPrimitiveAttributes, checkSharedVertexViews } from './validate-attributes.ts';
import { checkMaterialNumbers, textureBindings } from './validate-materials.ts';
import {
  alphaModeNote,
  checkAnimations,
  checkCameras,
  checkMorphTargets,
  checkNodeFeatures,
  checkSamplers,
  checkSkins,
} from './validate-features.ts';
import {
  bounded,
  boundedArray,
  describeValue,
  fail,
  finiteArray,
  index,
  indexArray,
  integer,
  isObject,
  list,
  MAX_OBJECTS,
  required,
  type Json,
} from './validate-values.ts';

import { checkGpuInstancing } from './gpu-instancing.ts';

export { fail, list };

/** Extensions a file may require: those pathwise reads (see docs/gltf.md). */
export const SUPPORTED_REQUIRED = new Set([
  'KHR_materials_anisotropy',
  'KHR_materials_clearcoat',
  'KHR_materials_diffuse_transmission',
  'KHR_materials_dispersion',
  'KHR_materials_emissive_strength',
  'KHR_materials_ior',
  'KHR_materials_iridescence',
  'KHR_materials_pbrSpecularGlossiness',
  'KHR_materials_sheen',
  'KHR_materials_specular',
  'KHR_materials_transmission',
  'KHR_materials_unlit',
  'KHR_materials_variants',
  'KHR_materials_volume',
  'KHR_mesh_quantization',
  'KHR_texture_transform',
  'EXT_mesh_gpu_instancing',
]);

export const GLTF_LIMITS = {
  /**
   * Distinct triangles one glTF file may hold in memory (the scene format's per-scene
   * limit): a mesh used by several nodes counts once, since its uses become instances
   * of one copy (accel/instances.ts).
   */
  triangles: 10_000_000,
  /** Mesh instances of the scene: nodes with a mesh plus EXT_mesh_gpu_instancing rows. */
  instances: 1_000_000,
  /** Elements of one accessor. */
  accessorCount: 1 << 28,
  /** Nodes, meshes, accessors… of one kind. */
  objects: MAX_OBJECTS,
  /** All buffers of one file together (the scene format's limit for one mesh file). */
  bufferBytes: 1024 * 1024 * 1024,
} as const;

export const COMPONENT_SIZE: Record<number, number> = {
  5120: 1,
  5121: 1,
  5122: 2,
  5123: 2,
  5125: 4,
  5126: 4,
};
export const TYPE_SIZE: Record<string, number> = {
  SCALAR: 1,
  VEC2: 2,
  VEC3: 3,
  VEC4: 4,
  MAT2: 4,
  MAT3: 9,
  MAT4: 16,
};
export const MODE_TRIANGLES = 4;
export const MODE_TRIANGLE_STRIP = 5;
export const MODE_TRIANGLE_FAN = 6;

/** What the loader needs from the checked document. */
export interface GltfSummary {
  /** Index of the scene to instance, or −1 when the file has none. */
  scene: number;
  /** Distinct triangles of the meshes the scene uses (before zero-area ones are dropped). */
  triangles: number;
  /** Mesh instances of the scene (nodes with a mesh, EXT_mesh_gpu_instancing rows). */
  instances: number;
  /** Indices of textures without an image source (§5.29: `source` is optional); ignored. */
  sourceless: number[];
  /** Notes for what is valid but not rendered (texture coordinate sets beyond 1). */
  notes: string[];
}

/** The version this reader implements (glTF 2.0 §3.2 "Asset"). */
const SUPPORTED_MINOR = 0;

/** §3.2: "version" and "minVersion" are "<major>.<minor>"; a loader refuses a minVersion it lacks. */
function checkAsset(json: Json): void {
  const asset = json.asset;
  if (!isObject(asset) || asset.version === undefined) fail('asset.version', 'is required');
  const parse = (key: string): [number, number] | undefined => {
    const v = asset[key];
    if (v === undefined) return undefined;
    const m = typeof v === 'string' ? /^([0-9]+)\.([0-9]+)$/.exec(v) : null;
    if (m === null)
      fail(`asset.${key}`, `must be a string "<major>.<minor>", got ${describeValue(v)}`);
    return [Number(m[1]), Number(m[2])];
  };
  const [major, minor] = parse('version')!;
  if (major !== 2)
    fail('asset.version', `glTF ${quote(asset.version as string)} is not supported, only 2.x`);
  const min = parse('minVersion');
  if (min !== undefined) {
    if (min[0] > major || (min[0] === major && min[1] > minor))
      fail(
        'asset.minVersion',
        `${quote(asset.minVersion as string)} is greater than the version ${quote(asset.version as string)}`,
      );
    if (min[0] !== 2 || min[1] > SUPPORTED_MINOR)
      fail(
        'asset.minVersion',
        `the file needs glTF ${quote(asset.minVersion as string)}, and pathwise reads glTF 2.0 (§3.2: a loader must refuse a minVersion it does not support)`,
      );
  }
}

/**
 * Checks everything that does not need the buffers' bytes; `decodable` names the
 * compression extensions this platform can decode (load.ts), which a file may require.
 * Throws GltfError.
 */
export function validateGltfJson(
  json: unknown,
  decodable: ReadonlySet<string> = new Set(),
): GltfSummary {
  if (!isObject(json)) fail('document', 'the glTF JSON must be an object');
  checkAsset(json);
  const req = json.extensionsRequired ?? [];
  if (!Array.isArray(req)) fail('extensionsRequired', 'must be an array');
  // All of them in one message: a user who fixes one should not meet the next.
  const missing = req.filter(
    (name) => typeof name !== 'string' || !(SUPPORTED_REQUIRED.has(name) || decodable.has(name)),
  );
  if (missing.length > 0) {
    const names = missing.map((n) => (typeof n === 'string' ? quote(n) : 'a non-string'));
    fail(
      'extensionsRequired',
      `the file requires ${names.join(', ')}, which pathwise does not support`,
    );
  }
  const used = Array.isArray(json.extensionsUsed) ? json.extensionsUsed : [];
  // glTF 2.0 §3.12: every extension in extensionsRequired is also in extensionsUsed.
  for (const name of req) {
    if (!used.includes(name))
      fail('extensionsRequired', `${quote(name as string)} is not listed in extensionsUsed`);
  }
  const quantized = used.includes('KHR_mesh_quantization');
  const buffers = list(json, 'buffers');
  const views = list(json, 'bufferViews');
  const accessors = list(json, 'accessors');
  const images = list(json, 'images');
  const samplers = list(json, 'samplers');
  const textures = list(json, 'textures');
  const materials = list(json, 'materials');
  const meshes = list(json, 'meshes');
  const nodes = list(json, 'nodes');
  const scenes = list(json, 'scenes');
  const cameras = list(json, 'cameras');
  const arrays = { accessors, nodes, meshes, cameras };
  const notes: string[] = [];

  let bufferBytes = 0;
  buffers.forEach((b, i) => {
    bufferBytes += required(b, 'byteLength', `buffers[${i}]`, 1);
    if (bufferBytes > GLTF_LIMITS.bufferBytes) {
      fail(
        `buffers[${i}]`,
        `the buffers add up to more than ${GLTF_LIMITS.bufferBytes} bytes, the limit`,
      );
    }
    if (b.uri !== undefined && typeof b.uri !== 'string')
      fail(`buffers[${i}].uri`, `must be a string, got ${describeValue(b.uri)}`);
  });
  views.forEach((v, i) => {
    const p = `bufferViews[${i}]`;
    if (index(v, 'buffer', p, buffers.length, 'buffers') === undefined)
      fail(`${p}.buffer`, 'is required');
    integer(v, 'byteOffset', p, 0);
    required(v, 'byteLength', p, 1);
    const stride = integer(v, 'byteStride', p, 4, 252);
    if (stride !== undefined && stride % 4 !== 0)
      fail(`${p}.byteStride`, `must be a multiple of 4, got ${stride}`);
  });
  accessors.forEach((a, i) => {
    const p = `accessors[${i}]`;
    index(a, 'bufferView', p, views.length, 'bufferViews');
    integer(a, 'byteOffset', p, 0);
    const ct = required(a, 'componentType', p, 0);
    if (!(ct in COMPONENT_SIZE)) fail(`${p}.componentType`, `${ct} is not a glTF component type`);
    required(a, 'count', p, 1, GLTF_LIMITS.accessorCount);
    if (typeof a.type !== 'string' || !(a.type in TYPE_SIZE))
      fail(
        `${p}.type`,
        `${typeof a.type === 'string' ? quote(a.type) : describeValue(a.type)} is not a glTF accessor type`,
      );
    if (a.normalized !== undefined && typeof a.normalized !== 'boolean')
      fail(`${p}.normalized`, `must be a boolean, got ${describeValue(a.normalized)}`);
    // accessor.schema.json: normalized "MUST NOT be set to true" for FLOAT and UNSIGNED_INT.
    if (a.normalized === true && (ct === 5126 || ct === 5125))
      fail(
        `${p}.normalized`,
        `must not be true for component type ${ct} (only (U)BYTE and (U)SHORT)`,
      );
    const sparse = a.sparse;
    if (sparse !== undefined) {
      if (!isObject(sparse) || !isObject(sparse.indices) || !isObject(sparse.values))
        fail(`${p}.sparse`, 'must have indices and values');
      required(sparse, 'count', `${p}.sparse`, 1, a.count as number);
      for (const k of ['indices', 'values'] as const) {
        const s = sparse[k] as Json;
        if (index(s, 'bufferView', `${p}.sparse.${k}`, views.length, 'bufferViews') === undefined)
          fail(`${p}.sparse.${k}.bufferView`, 'is required');
        integer(s, 'byteOffset', `${p}.sparse.${k}`, 0);
      }
      const ict = required(sparse.indices as Json, 'componentType', `${p}.sparse.indices`, 0);
      if (ict !== 5121 && ict !== 5123 && ict !== 5125)
        fail(`${p}.sparse.indices.componentType`, `must be an unsigned integer type, got ${ict}`);
    }
  });
  images.forEach((im, i) => {
    const p = `images[${i}]`;
    const view = index(im, 'bufferView', p, views.length, 'bufferViews');
    if (view === undefined && typeof im.uri !== 'string')
      fail(p, 'has neither a uri nor a bufferView');
  });
  checkSamplers(samplers);
  const sourceless: number[] = [];
  textures.forEach((t, i) => {
    if (index(t, 'source', `textures[${i}]`, images.length, 'images') === undefined)
      sourceless.push(i);
    index(t, 'sampler', `textures[${i}]`, samplers.length, 'samplers');
  });
  const textureInfo = (o: unknown, p: string): void => {
    if (o === undefined) return;
    if (!isObject(o)) fail(p, `must be an object, got ${describeValue(o)}`);
    if (index(o, 'index', p, textures.length, 'textures') === undefined)
      fail(`${p}.index`, 'is required');
    integer(o, 'texCoord', p, 0, 1 << 16);
  };
  materials.forEach((m, i) => {
    const p = `materials[${i}]`;
    checkMaterialNumbers(m, p);
    const alpha = alphaModeNote(m, p);
    if (alpha !== undefined && notes.length < 10) notes.push(alpha);
    for (const b of textureBindings(m, p)) textureInfo(b.info, b.path);
  });
  meshes.forEach((mesh, i) => {
    const prims = list(mesh, 'primitives', `meshes[${i}].primitives`);
    if (prims.length === 0) fail(`meshes[${i}].primitives`, 'must not be empty');
    prims.forEach((pr, j) => {
      const p = `meshes[${i}].primitives[${j}]`;
      checkPrimitiveAttributes(pr, p, accessors, quantized);
      const ind = index(pr, 'indices', p, accessors.length, 'accessors');
      if (ind !== undefined) {
        const a = accessors[ind];
        if (a.type !== 'SCALAR' || ![5121, 5123, 5125].includes(a.componentType as number)) {
          fail(`${p}.indices`, `accessors[${ind}] must be SCALAR of an unsigned integer type`);
        }
      }
      const mat = index(pr, 'material', p, materials.length, 'materials');
      if (mat !== undefined) {
        const attributes = pr.attributes as Json;
        for (const b of textureBindings(materials[mat], `materials[${mat}]`)) {
          const t = isObject(b.info) ? textures[b.info.index as number] : undefined;
          if (t === undefined) continue;
          // A set the primitive lacks is a broken file even when the texture has no
          // source (and is then ignored): the binding itself is invalid (§3.9.2).
          if (attributes[`TEXCOORD_${b.set}`] === undefined)
            fail(
              `${p}.attributes`,
              `has no TEXCOORD_${b.set}, which its material's ${b.path.slice(b.path.indexOf('.') + 1)} reads`,
            );
          if (t.source === undefined) continue;
          if (b.set > 1 && notes.length < 10)
            notes.push(
              `${b.path}: reads TEXCOORD_${b.set}; pathwise reads only sets 0 and 1, so the texture is ignored`,
            );
        }
      }
      integer(pr, 'mode', p, 0, 6);
    });
    checkMorphTargets(mesh, `meshes[${i}]`);
  });
  checkSharedVertexViews(json);
  checkCameras(cameras);
  const skins = checkSkins(json, arrays);
  checkAnimations(json, arrays);
  const parent = new Int32Array(nodes.length).fill(-1);
  const gpuInstances = new Float64Array(nodes.length);
  nodes.forEach((n, i) => {
    const p = `nodes[${i}]`;
    index(n, 'mesh', p, meshes.length, 'meshes');
    index(n, 'camera', p, cameras.length, 'cameras');
    finiteArray(n, 'matrix', p, 16);
    finiteArray(n, 'translation', p, 3);
    finiteArray(n, 'rotation', p, 4);
    // §5.25: `rotation` is a unit quaternion. Writers round (the corpus is within 3e-7 of
    // unit); one far from unit, or zero, names no rotation at all.
    if (Array.isArray(n.rotation)) {
      const l = Math.hypot(...(n.rotation as number[]));
      if (!(Math.abs(l - 1) <= 1e-2))
        fail(`${p}.rotation`, `is not a unit quaternion (length ${l}); glTF requires one`);
    }
    finiteArray(n, 'scale', p, 3);
    checkNodeFeatures(n, p, arrays, skins);
    gpuInstances[i] = checkGpuInstancing(n, p, accessors, GLTF_LIMITS.instances);
    for (const c of indexArray(n, 'children', p, nodes.length, 'nodes')) {
      if (c === i) fail(`${p}.children`, 'contains the node itself');
      if (parent[c] !== -1)
        fail(
          `nodes[${c}]`,
          `is a child of both nodes[${parent[c]}] and nodes[${i}]; glTF nodes form trees`,
        );
      parent[c] = i;
    }
  });
  // With one parent each, a cycle is a chain of parents that never reaches a root.
  const state = new Uint8Array(nodes.length); // 0 unknown, 1 on the current chain, 2 reaches a root
  for (let i = 0; i < nodes.length; i++) {
    let k = i;
    while (k !== -1 && state[k] === 0) {
      state[k] = 1;
      k = parent[k];
    }
    if (k !== -1 && state[k] === 1)
      fail(`nodes[${k}]`, 'is its own ancestor (the node hierarchy has a cycle)');
    for (k = i; k !== -1 && state[k] === 1; k = parent[k]) state[k] = 2;
  }
  scenes.forEach((s, i) => {
    for (const r of indexArray(s, 'nodes', `scenes[${i}]`, nodes.length, 'nodes')) {
      if (parent[r] !== -1)
        fail(
          `scenes[${i}].nodes`,
          `nodes[${r}] is a root of the scene but also a child of nodes[${parent[r]}]`,
        );
    }
  });
  const scene =
    scenes.length === 0 ? -1 : (index(json, 'scene', 'document', scenes.length, 'scenes') ?? 0);
  const counts =
    scene < 0
      ? { triangles: 0, instances: 0 }
      : countTriangles(scenes[scene], nodes, meshes, accessors, gpuInstances);
  return {
    scene,
    ...counts,
    sourceless,
    notes,
  };
}

/** Triangles of one primitive from its accessor counts (0 for points and lines). */
export function primitiveTriangles(pr: Json, accessors: Json[]): number {
  const mode = (pr.mode as number | undefined) ?? MODE_TRIANGLES;
  const attributes = pr.attributes as Json;
  const pos = attributes.POSITION;
  if (typeof pos !== 'number') return 0;
  const n =
    pr.indices !== undefined
      ? (accessors[pr.indices as number].count as number)
      : (accessors[pos].count as number);
  if (mode === MODE_TRIANGLES) return Math.floor(n / 3);
  if (mode === MODE_TRIANGLE_STRIP || mode === MODE_TRIANGLE_FAN) return Math.max(0, n - 2);
  return 0;
}

/**
 * Distinct triangles and instances of the meshes the scene reaches, refused past
 * GLTF_LIMITS: a mesh counts its triangles once however many nodes use it.
 */
function countTriangles(
  scene: Json,
  nodes: Json[],
  meshes: Json[],
  accessors: Json[],
  gpuInstances: Float64Array,
): { triangles: number; instances: number } {
  const perMesh = meshes.map((m) =>
    (m.primitives as Json[]).reduce((s, pr) => s + primitiveTriangles(pr, accessors), 0),
  );
  const counted = new Uint8Array(meshes.length);
  let triangles = 0;
  let instances = 0;
  const stack = ((scene.nodes as number[] | undefined) ?? []).slice();
  while (stack.length > 0) {
    const k = stack.pop()!;
    const n = nodes[k];
    if (typeof n.mesh === 'number') {
      instances += gpuInstances[k] > 0 ? gpuInstances[k] : 1;
      if (instances > GLTF_LIMITS.instances) {
        fail(
          'scene',
          `has more than ${GLTF_LIMITS.instances.toLocaleString('en-US')} mesh instances, the limit`,
        );
      }
      if (counted[n.mesh] === 0) {
        counted[n.mesh] = 1;
        triangles += perMesh[n.mesh];
        if (triangles > GLTF_LIMITS.triangles) {
          fail(
            'scene',
            `uses meshes of more than ${GLTF_LIMITS.triangles.toLocaleString('en-US')} distinct triangles, the limit`,
          );
        }
      }
    }
    for (const c of (n.children as number[] | undefined) ?? []) stack.push(c);
  }
  return { triangles, instances };
}
