/**
 * EXT_mesh_gpu_instancing (Khronos extension, "Transformation Order"): a node with a
 * mesh and this extension draws the mesh once per instance, never on its own, at
 *   WorldPosition = NodeWorld × (T × R × S) × VertexPosition,
 * with T, R and S read from the accessors TRANSLATION (VEC3 float), ROTATION (VEC4
 * float, or normalized byte or short: KHR_mesh_quantization's encodings) and SCALE
 * (VEC3 float), each optional (identity where absent), all of one count.
 *
 * `checkGpuInstancing` refuses a malformed extension from the JSON alone (before any
 * buffer is read): wrong types, counts that differ, more instances than the cap.
 * `instanceMatrices` reads the per-instance TRS (after decoding) and refuses
 * non-finite values, naming the accessor and the instance.
 */
import type { Document } from '@gltf-transform/core';
import { readFloats } from './accessors.ts';
import { GltfError } from './errors.ts';
import { multiply, nodeMatrix as trsMatrix, type Mat4 } from './transforms.ts';
import { fail, index, isObject, type Json } from './validate-values.ts';

export const GPU_INSTANCING = 'EXT_mesh_gpu_instancing';

const FLOAT = 5126;
const BYTE = 5120;
const SHORT = 5122;

/** The attributes this reader uses, their type and allowed component types. */
const TRS: readonly [string, string, readonly number[]][] = [
  ['TRANSLATION', 'VEC3', [FLOAT]],
  ['ROTATION', 'VEC4', [FLOAT, BYTE, SHORT]],
  ['SCALE', 'VEC3', [FLOAT]],
];

/**
 * Instances the extension of node `n` (at JSON path `p`) declares, 0 without the
 * extension; fails on malformed content or more than `cap` instances.
 */
export function checkGpuInstancing(n: Json, p: string, accessors: Json[], cap: number): number {
  const ext = isObject(n.extensions) ? n.extensions[GPU_INSTANCING] : undefined;
  if (ext === undefined) return 0;
  const ep = `${p}.extensions.${GPU_INSTANCING}`;
  if (!isObject(ext)) fail(ep, 'must be an object');
  if (!isObject(ext.attributes)) fail(`${ep}.attributes`, 'must be an object');
  let count = -1;
  let first = '';
  for (const [name, type, components] of TRS) {
    const ap = `${ep}.attributes.${name}`;
    const i = index(ext.attributes, name, `${ep}.attributes`, accessors.length, 'accessors');
    if (i === undefined) continue;
    const a = accessors[i];
    if (a.type !== type || !components.includes(a.componentType as number))
      fail(
        ap,
        `accessors[${i}] must be ${type} of ${name === 'ROTATION' ? 'float, or normalized byte or short' : 'float'}`,
      );
    if (a.componentType !== FLOAT && a.normalized !== true)
      fail(ap, `accessors[${i}]: an integer ROTATION must be normalized`);
    const c = a.count as number;
    if (count < 0) {
      count = c;
      first = name;
    } else if (c !== count) {
      fail(
        ap,
        `accessors[${i}] has ${c} elements, but ${first} has ${count}: all must have one count`,
      );
    }
    if (c > cap)
      fail(
        ap,
        `declares ${c.toLocaleString('en-US')} instances, more than the limit of ${cap.toLocaleString('en-US')}`,
      );
  }
  if (count < 0) fail(`${ep}.attributes`, 'has none of TRANSLATION, ROTATION and SCALE');
  // Without a mesh there is nothing to draw: the rows are ignored (flatten.ts reads them
  // only for nodes with a mesh).
  return typeof n.mesh === 'number' ? count : 0;
}

/** Whether a (validated) node carries the extension. */
export function hasGpuInstancing(n: Json): boolean {
  return isObject(n.extensions) && n.extensions[GPU_INSTANCING] !== undefined;
}

/**
 * Object-to-world matrices of the instances of nodes[node], given the node's world
 * matrix: NodeWorld × (T × R × S) for each, handed to `add` in instance order. Throws
 * GltfError on a non-finite value.
 */
export function instanceMatrices(
  doc: Document,
  json: Json,
  node: number,
  world: Mat4,
  add: (m: Mat4, instance: number) => void,
): void {
  const n = (json.nodes as Json[])[node];
  const ext = (n.extensions as Json)[GPU_INSTANCING] as Json;
  const attributes = ext.attributes as Json;
  const accessors = doc.getRoot().listAccessors();
  const ep = `nodes[${node}].extensions.${GPU_INSTANCING}.attributes`;
  const read = (name: string, size: number): Float32Array | null => {
    const i = attributes[name];
    if (typeof i !== 'number') return null;
    const data = readFloats(accessors[i]);
    for (let k = 0; k < data.length; k++) {
      if (!Number.isFinite(data[k]))
        throw new GltfError(
          `${ep}.${name}: instance ${Math.floor(k / size)} has a non-finite value`,
        );
    }
    return data;
  };
  const t = read('TRANSLATION', 3);
  const r = read('ROTATION', 4);
  const s = read('SCALE', 3);
  const count = (t?.length ?? 0) / 3 || (r?.length ?? 0) / 4 || (s?.length ?? 0) / 3;
  for (let k = 0; k < count; k++) {
    const local: Json = {};
    if (t !== null) local.translation = [t[3 * k], t[3 * k + 1], t[3 * k + 2]];
    if (r !== null) local.rotation = [r[4 * k], r[4 * k + 1], r[4 * k + 2], r[4 * k + 3]];
    if (s !== null) local.scale = [s[3 * k], s[3 * k + 1], s[3 * k + 2]];
    add(multiply(world, trsMatrix(local)), k);
  }
}
