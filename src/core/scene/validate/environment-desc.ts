/**
 * Validation of the scene's `environment`: a constant `[r, g, b]`, or an environment map
 * `{ "type": "map", "file", "scale", "rotationY" }` (docs/scene-format.md, Environment
 * maps). The map's file is only checked by name here; `resolveSceneFiles` reads it.
 */
import { RADIANCE } from './radiance.ts';
import type { EnvironmentMapDesc, Vec3 } from '../format/types.ts';
import {
  NON_NEGATIVE,
  describe,
  describeType,
  expectKnownKeys,
  expectNumber,
  expectOneOf,
  expectString,
  expectVec3,
  type Problems,
} from './validate-helpers.ts';

const MAP_KEYS = ['type', 'file', 'scale', 'rotationY'];

export function envMapFileKind(file: string): 'hdr' | 'pfm' | undefined {
  const m = /\.(hdr|pfm)$/i.exec(file);
  return m === null ? undefined : (m[1].toLowerCase() as 'hdr' | 'pfm');
}

export interface CheckedEnvironment {
  constant: Vec3;
  map: EnvironmentMapDesc | null;
}

export function checkEnvironment(
  value: unknown,
  problems: Problems,
): CheckedEnvironment | undefined {
  if (value === undefined) return { constant: [0, 0, 0], map: null };
  if (Array.isArray(value)) {
    const constant = expectVec3(value, 'environment', problems, RADIANCE);
    return constant === undefined ? undefined : { constant, map: null };
  }
  if (typeof value !== 'object' || value === null) {
    problems.push(
      `environment must be [r, g, b] or an environment map object, got ${describeType(value)}`,
    );
    return undefined;
  }
  const obj = value as Record<string, unknown>;
  const before = problems.length;
  expectOneOf(obj.type, 'environment.type', ['map'], problems);
  expectKnownKeys(obj, 'environment', MAP_KEYS, problems);
  const file = expectString(obj.file, 'environment.file', problems);
  if (file !== undefined && envMapFileKind(file) === undefined) {
    problems.push(`environment.file must name an .hdr or .pfm file, got ${describe(file)}`);
  }
  let scale: Vec3 | undefined = [1, 1, 1];
  if (typeof obj.scale === 'number' || obj.scale === null || typeof obj.scale === 'string') {
    const s = expectNumber(obj.scale, 'environment.scale', problems, NON_NEGATIVE);
    scale = s === undefined ? undefined : [s, s, s];
  } else if (obj.scale !== undefined) {
    scale = expectVec3(obj.scale, 'environment.scale', problems, NON_NEGATIVE);
  }
  const rotationY =
    obj.rotationY === undefined
      ? 0
      : expectNumber(obj.rotationY, 'environment.rotationY', problems);
  if (problems.length > before) return undefined;
  return {
    constant: [0, 0, 0],
    map: { type: 'map', file: file!, scale: scale!, rotationY: rotationY!, image: null },
  };
}
