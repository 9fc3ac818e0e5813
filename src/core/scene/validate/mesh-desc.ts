/**
 * Validation of a `mesh` shape's JSON (docs/scene-format.md, Meshes). An inline mesh is
 * turned into world-space triangles here; a mesh `file` is only checked by name, and
 * read later by `resolveSceneFiles` (files.ts), which needs a way to reach the file.
 *
 * Inline arrays can be long (hundreds of thousands of numbers), so each array reports
 * its first bad element only, not one problem per element.
 */
import { buildMeshData, MeshError } from '../../geometry/mesh-data.ts';
import { transformProblem } from '../../math/affine.ts';
import type { MeshDesc, Scene } from '../format/types.ts';
import {
  describe,
  describeType,
  expectString,
  indexPath,
  type Problems,
} from './validate-helpers.ts';

export const MESH_KEYS = [
  'type',
  'material',
  'positions',
  'indices',
  'normals',
  'file',
  'transform',
];

/** File kinds a mesh may name, by extension. */
export function meshFileKind(file: string): 'obj' | 'ply' | undefined {
  const m = /\.(obj|ply)$/i.exec(file);
  return m === null ? undefined : (m[1].toLowerCase() as 'obj' | 'ply');
}

/** Validates the keys of a mesh other than `type` and `material` (checked by the caller). */
export function checkMesh(
  obj: Record<string, unknown>,
  path: string,
  material: string | undefined,
  problems: Problems,
): MeshDesc | undefined {
  const before = problems.length;
  const transform =
    obj.transform === undefined ? null : checkTransform(obj.transform, path, problems);
  if (obj.file !== undefined) {
    for (const key of ['positions', 'indices', 'normals']) {
      if (obj[key] !== undefined) {
        problems.push(`${path} has both file and ${key}: a mesh takes its triangles from one`);
      }
    }
    const file = expectString(obj.file, `${path}.file`, problems);
    if (file !== undefined && meshFileKind(file) === undefined) {
      problems.push(`${path}.file must name an .obj or .ply file, got ${describe(file)}`);
    }
    if (problems.length > before) return undefined;
    return { type: 'mesh', material: material!, file: file!, transform, data: null };
  }
  if (obj.positions === undefined) {
    problems.push(`${path} needs positions (a flat array of numbers) or file`);
    return undefined;
  }
  const positions = numberArray(obj.positions, `${path}.positions`, problems);
  if (positions === undefined) return undefined;
  const vertices = positions.length / 3;
  let indices: Uint32Array | undefined;
  if (obj.indices === undefined) {
    if (vertices % 3 !== 0) {
      problems.push(
        `${path}.positions holds ${vertices} vertices; without indices they are taken three ` +
          `per triangle, so their number must be a multiple of 3`,
      );
    } else {
      indices = new Uint32Array(vertices);
      for (let i = 0; i < vertices; i++) indices[i] = i;
    }
  } else {
    indices = indexArray(obj.indices, `${path}.indices`, vertices, problems);
  }
  let normals: Float64Array | null = null;
  if (obj.normals !== undefined) {
    const n = numberArray(obj.normals, `${path}.normals`, problems);
    if (n !== undefined) {
      if (n.length !== positions.length) {
        problems.push(
          `${path}.normals must have the length of positions (${positions.length}), got ${n.length}`,
        );
      } else {
        for (let i = 0; i < n.length; i += 3) {
          if (n[i] === 0 && n[i + 1] === 0 && n[i + 2] === 0) {
            problems.push(`${path}.normals: the normal of vertex ${i / 3} is zero`);
            break;
          }
        }
        normals = n;
      }
    }
  }
  if (indices !== undefined && indices.length === 0) {
    problems.push(`${path} has no triangles`);
  }
  if (problems.length > before || indices === undefined) return undefined;
  try {
    const data = buildMeshData({ positions, indices, normals }, transform);
    return { type: 'mesh', material: material!, file: null, transform, data };
  } catch (e) {
    if (!(e instanceof MeshError)) throw e;
    problems.push(`${path}: ${e.message}`);
    return undefined;
  }
}

/** A flat array of finite numbers whose length is a multiple of 3, as a fresh Float64Array. */
function numberArray(value: unknown, path: string, problems: Problems): Float64Array | undefined {
  if (!Array.isArray(value)) {
    problems.push(`${path} must be a flat array of numbers, got ${describeType(value)}`);
    return undefined;
  }
  if (value.length % 3 !== 0) {
    problems.push(`${path} must have a length that is a multiple of 3, got ${value.length}`);
    return undefined;
  }
  const out = new Float64Array(value.length);
  for (let i = 0; i < value.length; i++) {
    const x = value[i];
    if (typeof x !== 'number' || !Number.isFinite(x)) {
      problems.push(`${indexPath(path, i)} must be a finite number, got ${describeType(x)}`);
      return undefined;
    }
    out[i] = x;
  }
  return out;
}

function indexArray(
  value: unknown,
  path: string,
  vertices: number,
  problems: Problems,
): Uint32Array | undefined {
  if (!Array.isArray(value)) {
    problems.push(`${path} must be a flat array of vertex indices, got ${describeType(value)}`);
    return undefined;
  }
  if (value.length % 3 !== 0) {
    problems.push(`${path} must have a length that is a multiple of 3, got ${value.length}`);
    return undefined;
  }
  const out = new Uint32Array(value.length);
  for (let i = 0; i < value.length; i++) {
    const x = value[i];
    if (typeof x !== 'number' || !Number.isInteger(x) || x < 0 || x >= vertices) {
      problems.push(
        `${indexPath(path, i)} must be a vertex index in [0, ${vertices - 1}], got ${describeType(x)}` +
          (vertices === 0 ? ' (positions is empty)' : ''),
      );
      return undefined;
    }
    out[i] = x;
  }
  return out;
}

/** A shape's `transform`: 16 finite numbers, row-major, affine and invertible. */
export function checkTransform(value: unknown, path: string, problems: Problems): number[] | null {
  const at = `${path}.transform`;
  if (!Array.isArray(value) || value.length !== 16) {
    problems.push(
      `${at} must be an array of 16 numbers (a row-major 4×4 matrix), got ${describeType(value)}`,
    );
    return null;
  }
  for (let i = 0; i < 16; i++) {
    const x = value[i];
    if (typeof x !== 'number' || !Number.isFinite(x)) {
      problems.push(`${indexPath(at, i)} must be a finite number, got ${describeType(x)}`);
      return null;
    }
  }
  const problem = transformProblem(value as number[]);
  if (problem !== undefined) {
    problems.push(`${at}: ${problem}`);
    return null;
  }
  return (value as number[]).slice();
}

/** Zero-area triangles the scene's meshes skipped (the spec asks renderers to report it). */
export function countSkippedTriangles(scene: Scene): number {
  let n = 0;
  for (const s of scene.shapes) {
    if ((s.type === 'mesh' || s.type === 'gltf') && s.data !== null) n += s.data.skipped;
  }
  return n;
}
