/**
 * Validation of the scene's `lights` (docs/scene-format.md, Lights): punctual lights of
 * KHR_lights_punctual's kinds and units, in the scene's own conventions (angles in
 * degrees, like `fovY`):
 * - `{ "type": "point", "position", "intensity", "color" }`, intensity in candela;
 * - `{ "type": "spot", "position", "direction", "intensity", "color", "innerConeAngle",
 *   "outerConeAngle" }`, candela, the cone in degrees from `direction`;
 * - `{ "type": "directional", "direction", "intensity", "color" }`, intensity in lux;
 * `direction` is where the light travels. `color` defaults to [1, 1, 1], the cone to
 * 0° and 45° (glTF's defaults), with 0 ≤ inner ≤ outer ≤ 90, outer > 0.
 */
import { MAX_RADIANCE } from './radiance.ts';
import { LIMITS, type LightDesc, type Vec3 } from '../format/types.ts';
import {
  NON_NEGATIVE,
  childPath,
  describeType,
  expectKnownKeys,
  expectNumber,
  expectObject,
  expectOneOf,
  expectVec3,
  indexPath,
  normalize,
  type Problems,
} from './validate-helpers.ts';

const TYPES = ['point', 'spot', 'directional'] as const;
const KEYS: Record<LightDesc['type'], string[]> = {
  point: ['type', 'position', 'intensity', 'color'],
  spot: ['type', 'position', 'direction', 'intensity', 'color', 'innerConeAngle', 'outerConeAngle'],
  directional: ['type', 'direction', 'intensity', 'color'],
};

/** The scene's `lights` (absent: none), or undefined after recording its problems. */
export function checkLights(value: unknown, problems: Problems): LightDesc[] | undefined {
  if (value === undefined) return [];
  if (!Array.isArray(value)) {
    problems.push(`lights must be an array, got ${describeType(value)}`);
    return undefined;
  }
  if (value.length > LIMITS.shapes) {
    problems.push(`lights must have at most ${LIMITS.shapes} entries, got ${value.length}`);
    return undefined;
  }
  const before = problems.length;
  const out = value.map((v, i) => checkLight(v, indexPath('lights', i), problems));
  return problems.length > before ? undefined : (out as LightDesc[]);
}

function checkLight(value: unknown, path: string, problems: Problems): LightDesc | undefined {
  const obj = expectObject(value, path, problems);
  if (obj === undefined) return undefined;
  const at = (key: string) => childPath(path, key);
  const type = expectOneOf(obj.type, at('type'), TYPES, problems);
  if (type === undefined) return undefined; // the allowed keys depend on the type
  const before = problems.length;
  expectKnownKeys(obj, path, KEYS[type], problems);
  const position: Vec3 | undefined =
    type === 'directional' ? [0, 0, 0] : expectVec3(obj.position, at('position'), problems);
  let direction: Vec3 | undefined = [0, 0, -1];
  if (type !== 'point') {
    const d = expectVec3(obj.direction, at('direction'), problems);
    direction = d === undefined ? undefined : normalize(d);
    if (d !== undefined && direction === undefined)
      problems.push(`${at('direction')} must be a non-zero vector of finite length, got [${d}]`);
  }
  const intensity = expectNumber(obj.intensity, at('intensity'), problems, NON_NEGATIVE);
  const color =
    obj.color === undefined
      ? ([1, 1, 1] as Vec3)
      : expectVec3(obj.color, at('color'), problems, NON_NEGATIVE);
  // The radiance bound's reason (radiance.ts) applies to what a light gives a surface a
  // unit away.
  if (
    intensity !== undefined &&
    color !== undefined &&
    intensity * Math.max(...color) > MAX_RADIANCE
  )
    problems.push(
      `${at('intensity')} × color must be at most 1e12 in every channel, got ${intensity} × [${color}]`,
    );
  let inner = 0;
  let outer = 45;
  if (type === 'spot') {
    const i =
      obj.innerConeAngle === undefined
        ? 0
        : expectNumber(obj.innerConeAngle, at('innerConeAngle'), problems, {
            ok: (x) => x >= 0 && x < 90,
            rule: 'be in [0, 90) degrees',
          });
    const o =
      obj.outerConeAngle === undefined
        ? 45
        : expectNumber(obj.outerConeAngle, at('outerConeAngle'), problems, {
            ok: (x) => x > 0 && x <= 90,
            rule: 'be in (0, 90] degrees',
          });
    if (i !== undefined && o !== undefined && i > o)
      problems.push(`${at('innerConeAngle')} must be at most outerConeAngle (${o}), got ${i}`);
    inner = i ?? 0;
    outer = o ?? 45;
  }
  if (problems.length > before) return undefined;
  return {
    type,
    position: position!,
    direction: direction!,
    color: color!,
    intensity: intensity!,
    innerConeAngle: inner,
    outerConeAngle: outer,
    range: null,
  };
}
