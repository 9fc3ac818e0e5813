/**
 * Structural checks of a glTF 2.0 JSON document before glTF-Transform reads
 * it: every index in range, every accessor inside its buffer view and every
 * view inside its buffer, aligned; the node graph a forest; the triangles
 * the default scene instances counted against the limit. glTF-Transform
 * (like most loaders) trusts these and fails deep inside with a RangeError,
 * or allocates what a lying count asks for; here each gets one message
 * naming its place in the file (glTF 2.0 §3.6 "Binary data storage", §5
 * "Properties reference").
 */
import { quote } from '../util/message.ts';
import { GltfError } from './errors.ts';

type Json = Record<string, unknown>;

/** Extensions a file may require: those pathwise reads (see docs/gltf.md). */
export const SUPPORTED_REQUIRED = new Set([
  'KHR_materials_emissive_strength',
  'KHR_materials_ior',
  'KHR_materials_specular',
  'KHR_materials_transmission',
  'KHR_mesh_quantization',
  'KHR_texture_transform',
]);

export const GLTF_LIMITS = {
  /** Triangles one glTF file may instance (the scene format's per-scene limit). */
  triangles: 10_000_000,
  /** Elements of one accessor. */
  accessorCount: 1 << 28,
  /** Nodes, meshes, accessors… of one kind. */
  objects: 1_000_000,
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

function isObject(v: unknown): v is Json {
  return typeof v === 'object' && v !== null && !Array.isArray(v);
}

export function fail(path: string, what: string): never {
  throw new GltfError(`${path}: ${what}`);
}

/** The array at json[key] (absent: empty), each element an object. */
export function list(json: Json, key: string, path = key): Json[] {
  const v = json[key];
  if (v === undefined) return [];
  if (!Array.isArray(v)) fail(path, 'must be an array');
  if (v.length > GLTF_LIMITS.objects)
    fail(path, `${v.length} entries, over the limit of ${GLTF_LIMITS.objects}`);
  v.forEach((e, i) => {
    if (!isObject(e)) fail(`${path}[${i}]`, 'must be an object');
  });
  return v as Json[];
}

function integer(
  o: Json,
  key: string,
  path: string,
  min: number,
  max = Number.MAX_SAFE_INTEGER,
): number | undefined {
  const v = o[key];
  if (v === undefined) return undefined;
  if (typeof v !== 'number' || !Number.isInteger(v) || v < min || v > max) {
    fail(
      `${path}.${key}`,
      `must be an integer in [${min}, ${max}], got ${typeof v === 'string' ? quote(v) : String(v)}`,
    );
  }
  return v;
}

function required(o: Json, key: string, path: string, min: number, max?: number): number {
  const v = integer(o, key, path, min, max);
  if (v === undefined) fail(`${path}.${key}`, 'is required');
  return v;
}

function index(o: Json, key: string, path: string, n: number, what: string): number | undefined {
  const v = o[key];
  if (v === undefined) return undefined;
  if (typeof v !== 'number' || !Number.isInteger(v) || v < 0 || v >= n) {
    fail(`${path}.${key}`, `refers to ${what}[${String(v)}], but the file has ${n}`);
  }
  return v;
}

function finiteArray(o: Json, key: string, path: string, length: number): void {
  const v = o[key];
  if (v === undefined) return;
  if (
    !Array.isArray(v) ||
    v.length !== length ||
    !v.every((x) => typeof x === 'number' && Number.isFinite(x))
  ) {
    fail(`${path}.${key}`, `must be ${length} finite numbers`);
  }
}

/** A number at o[key], if present, finite and within [min, max]. */
function bounded(o: unknown, key: string, path: string, min: number, max: number): void {
  if (!isObject(o) || o[key] === undefined) return;
  const v = o[key];
  if (typeof v !== 'number' || !(v >= min && v <= max)) {
    fail(
      `${path}.${key}`,
      `must be a number in [${min}, ${max}], got ${typeof v === 'number' ? String(v) : typeof v}`,
    );
  }
}

/** An array of `length` numbers at o[key], if present, each within [min, max]. */
function boundedArray(
  o: unknown,
  key: string,
  path: string,
  length: number,
  min: number,
  max: number,
): void {
  if (!isObject(o) || o[key] === undefined) return;
  const v = o[key];
  if (
    !Array.isArray(v) ||
    v.length !== length ||
    !v.every((x) => typeof x === 'number' && x >= min && x <= max)
  ) {
    fail(`${path}.${key}`, `must be ${length} numbers in [${min}, ${max}]`);
  }
}

/** The numbers of a material and of the extensions pathwise reads, as the glTF schemas bound them. */
function checkMaterialNumbers(m: Json, p: string): void {
  const pbr = m.pbrMetallicRoughness;
  const pp = `${p}.pbrMetallicRoughness`;
  boundedArray(pbr, 'baseColorFactor', pp, 4, 0, 1);
  bounded(pbr, 'metallicFactor', pp, 0, 1);
  bounded(pbr, 'roughnessFactor', pp, 0, 1);
  boundedArray(m, 'emissiveFactor', p, 3, 0, 1);
  bounded(m, 'alphaCutoff', p, 0, Number.MAX_VALUE);
  bounded(m.normalTexture, 'scale', `${p}.normalTexture`, -Number.MAX_VALUE, Number.MAX_VALUE);
  const ext = isObject(m.extensions) ? m.extensions : {};
  const e = (name: string): [unknown, string] => [ext[name], `${p}.extensions.${name}`];
  // Emission is radiance: bounded like every radiance of the scene format.
  const [es, esPath] = e('KHR_materials_emissive_strength');
  bounded(es, 'emissiveStrength', esPath, 0, 1e12);
  const [ior, iorPath] = e('KHR_materials_ior');
  bounded(ior, 'ior', iorPath, 0, 1e6);
  if (isObject(ior) && typeof ior.ior === 'number' && ior.ior > 0 && ior.ior < 1) {
    fail(`${iorPath}.ior`, `must be 0 or at least 1, got ${ior.ior}`);
  }
  const [tr, trPath] = e('KHR_materials_transmission');
  bounded(tr, 'transmissionFactor', trPath, 0, 1);
  const [spec, specPath] = e('KHR_materials_specular');
  bounded(spec, 'specularFactor', specPath, 0, 1);
  boundedArray(spec, 'specularColorFactor', specPath, 3, 0, 1e6);
  const infos: [unknown, string][] = [
    [isObject(pbr) ? pbr.baseColorTexture : undefined, `${pp}.baseColorTexture`],
    [isObject(pbr) ? pbr.metallicRoughnessTexture : undefined, `${pp}.metallicRoughnessTexture`],
    [m.normalTexture, `${p}.normalTexture`],
    [m.emissiveTexture, `${p}.emissiveTexture`],
  ];
  for (const [info, ip] of infos) {
    const tt =
      isObject(info) && isObject(info.extensions)
        ? info.extensions.KHR_texture_transform
        : undefined;
    if (tt === undefined) continue;
    const tp = `${ip}.extensions.KHR_texture_transform`;
    if (!isObject(tt)) fail(tp, 'must be an object');
    boundedArray(tt, 'offset', tp, 2, -1e9, 1e9);
    boundedArray(tt, 'scale', tp, 2, -1e9, 1e9);
    bounded(tt, 'rotation', tp, -1e9, 1e9);
    integer(tt, 'texCoord', tp, 0, 1 << 16);
  }
}

/** What the loader needs from the checked document. */
export interface GltfSummary {
  /** Index of the scene to instance, or −1 when the file has none. */
  scene: number;
  /** Triangles the scene instances (before zero-area ones are dropped). */
  triangles: number;
}

/**
 * Checks everything that does not need the buffers' bytes. Throws GltfError.
 */
export function validateGltfJson(json: unknown): GltfSummary {
  if (!isObject(json)) fail('document', 'the glTF JSON must be an object');
  const asset = json.asset;
  if (!isObject(asset) || typeof asset.version !== 'string') fail('asset.version', 'is required');
  if (!/^2\./.test(asset.version))
    fail('asset.version', `glTF ${quote(asset.version)} is not supported, only 2.x`);
  const req = json.extensionsRequired ?? [];
  if (!Array.isArray(req)) fail('extensionsRequired', 'must be an array');
  for (const name of req) {
    if (typeof name !== 'string' || !SUPPORTED_REQUIRED.has(name)) {
      fail(
        'extensionsRequired',
        `the file requires ${typeof name === 'string' ? quote(name) : 'a non-string'}, which pathwise does not support`,
      );
    }
  }
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
      fail(`buffers[${i}].uri`, 'must be a string');
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
        `${typeof a.type === 'string' ? quote(a.type) : 'missing'} is not a glTF accessor type`,
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
  samplers.forEach((s, i) => {
    for (const k of ['wrapS', 'wrapT']) {
      const w = s[k];
      if (w !== undefined && w !== 33071 && w !== 33648 && w !== 10497)
        fail(`samplers[${i}].${k}`, `${String(w)} is not a glTF wrap mode`);
    }
  });
  textures.forEach((t, i) => {
    index(t, 'source', `textures[${i}]`, images.length, 'images');
    index(t, 'sampler', `textures[${i}]`, samplers.length, 'samplers');
  });
  const textureInfo = (o: unknown, p: string): void => {
    if (o === undefined) return;
    if (!isObject(o)) fail(p, 'must be an object');
    if (index(o, 'index', p, textures.length, 'textures') === undefined)
      fail(`${p}.index`, 'is required');
    integer(o, 'texCoord', p, 0, 1 << 16);
  };
  materials.forEach((m, i) => {
    const p = `materials[${i}]`;
    checkMaterialNumbers(m, p);
    const pbr = m.pbrMetallicRoughness;
    if (isObject(pbr)) {
      textureInfo(pbr.baseColorTexture, `${p}.pbrMetallicRoughness.baseColorTexture`);
      textureInfo(
        pbr.metallicRoughnessTexture,
        `${p}.pbrMetallicRoughness.metallicRoughnessTexture`,
      );
    }
    for (const k of ['normalTexture', 'emissiveTexture', 'occlusionTexture'])
      textureInfo(m[k], `${p}.${k}`);
    const ext = isObject(m.extensions) ? m.extensions : {};
    const tr = ext.KHR_materials_transmission;
    if (isObject(tr))
      textureInfo(
        tr.transmissionTexture,
        `${p}.extensions.KHR_materials_transmission.transmissionTexture`,
      );
    const sp = ext.KHR_materials_specular;
    if (isObject(sp)) {
      textureInfo(sp.specularTexture, `${p}.extensions.KHR_materials_specular.specularTexture`);
      textureInfo(
        sp.specularColorTexture,
        `${p}.extensions.KHR_materials_specular.specularColorTexture`,
      );
    }
  });
  meshes.forEach((mesh, i) => {
    const prims = list(mesh, 'primitives', `meshes[${i}].primitives`);
    if (prims.length === 0) fail(`meshes[${i}].primitives`, 'must not be empty');
    prims.forEach((pr, j) => {
      const p = `meshes[${i}].primitives[${j}]`;
      if (!isObject(pr.attributes)) fail(`${p}.attributes`, 'is required');
      for (const [name, a] of Object.entries(pr.attributes)) {
        if (typeof a !== 'number' || !Number.isInteger(a) || a < 0 || a >= accessors.length) {
          fail(
            `${p}.attributes.${name}`,
            `refers to accessors[${String(a)}], but the file has ${accessors.length}`,
          );
        }
      }
      const ind = index(pr, 'indices', p, accessors.length, 'accessors');
      if (ind !== undefined) {
        const a = accessors[ind];
        if (a.type !== 'SCALAR' || ![5121, 5123, 5125].includes(a.componentType as number)) {
          fail(`${p}.indices`, `accessors[${ind}] must be SCALAR of an unsigned integer type`);
        }
      }
      index(pr, 'material', p, materials.length, 'materials');
      integer(pr, 'mode', p, 0, 6);
    });
  });
  const parent = new Int32Array(nodes.length).fill(-1);
  nodes.forEach((n, i) => {
    const p = `nodes[${i}]`;
    index(n, 'mesh', p, meshes.length, 'meshes');
    index(n, 'camera', p, cameras.length, 'cameras');
    finiteArray(n, 'matrix', p, 16);
    finiteArray(n, 'translation', p, 3);
    finiteArray(n, 'rotation', p, 4);
    finiteArray(n, 'scale', p, 3);
    const children = n.children ?? [];
    if (!Array.isArray(children)) fail(`${p}.children`, 'must be an array');
    for (const c of children) {
      if (typeof c !== 'number' || !Number.isInteger(c) || c < 0 || c >= nodes.length)
        fail(`${p}.children`, `refers to nodes[${String(c)}], but the file has ${nodes.length}`);
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
    const roots = s.nodes ?? [];
    if (!Array.isArray(roots)) fail(`scenes[${i}].nodes`, 'must be an array');
    for (const r of roots) {
      if (typeof r !== 'number' || !Number.isInteger(r) || r < 0 || r >= nodes.length)
        fail(
          `scenes[${i}].nodes`,
          `refers to nodes[${String(r)}], but the file has ${nodes.length}`,
        );
      if (parent[r] !== -1)
        fail(
          `scenes[${i}].nodes`,
          `nodes[${r}] is a root of the scene but also a child of nodes[${parent[r]}]`,
        );
    }
  });
  const scene =
    scenes.length === 0 ? -1 : (index(json, 'scene', 'document', scenes.length, 'scenes') ?? 0);
  return {
    scene,
    triangles: scene < 0 ? 0 : countTriangles(json, scenes[scene], nodes, meshes, accessors),
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

function countTriangles(
  json: Json,
  scene: Json,
  nodes: Json[],
  meshes: Json[],
  accessors: Json[],
): number {
  const perMesh = meshes.map((m) =>
    (m.primitives as Json[]).reduce((s, pr) => s + primitiveTriangles(pr, accessors), 0),
  );
  let total = 0;
  const stack = ((scene.nodes as number[] | undefined) ?? []).slice();
  while (stack.length > 0) {
    const n = nodes[stack.pop()!];
    if (typeof n.mesh === 'number') {
      total += perMesh[n.mesh];
      if (total > GLTF_LIMITS.triangles) {
        fail(
          'scene',
          `instances more than ${GLTF_LIMITS.triangles.toLocaleString('en-US')} triangles, the limit`,
        );
      }
    }
    for (const c of (n.children as number[] | undefined) ?? []) stack.push(c);
  }
  void json;
  return total;
}
