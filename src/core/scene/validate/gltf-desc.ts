/**
 * Validation of a `gltf` shape's JSON (docs/scene-format.md, Meshes from glTF). The file
 * is only checked by name here; `resolveSceneFiles` (files.ts) reads and loads it, which
 * needs a way to reach the file and the platform's image decoder.
 */
import { checkTransform } from './mesh-desc.ts';
import type { GltfDesc } from '../format/types.ts';
import { describe, expectString, type Problems } from './validate-helpers.ts';

export const GLTF_KEYS = ['type', 'file', 'transform', 'variant'];

/** Whether a file name is a glTF model by its extension. */
export function isGltfFile(file: string): boolean {
  return /\.(gltf|glb)$/i.test(file);
}

/** Validates the keys of a gltf shape other than `type` (checked by the caller). */
export function checkGltfShape(
  obj: Record<string, unknown>,
  path: string,
  problems: Problems,
): GltfDesc | undefined {
  const before = problems.length;
  const transform =
    obj.transform === undefined ? null : checkTransform(obj.transform, path, problems);
  if (obj.file === undefined) {
    problems.push(`${path} needs file (a .gltf or .glb file, relative to the scene file)`);
    return undefined;
  }
  const file = expectString(obj.file, `${path}.file`, problems);
  if (file !== undefined && !isGltfFile(file)) {
    problems.push(`${path}.file must name a .gltf or .glb file, got ${describe(file)}`);
  }
  // pathwise's addition (docs/scene-format.md, In pathwise: material variants).
  const variant =
    obj.variant === undefined ? undefined : expectString(obj.variant, `${path}.variant`, problems);
  if (problems.length > before) return undefined;
  return {
    type: 'gltf',
    file: file!,
    transform,
    ...(variant !== undefined && { variant }),
    data: null,
  };
}
