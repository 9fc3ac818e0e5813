/**
 * KHR_lights_punctual in a glTF file: the document's `extensions.KHR_lights_punctual.lights`
 * checked (one GltfError naming the JSON path), and each node's light placed in world
 * space while flatten.ts walks the scene. Per the extension's README:
 * - a light sits at its node's origin and shines along the node's local −z; the node's
 *   scale moves and turns it but changes no property (range, intensity, cone);
 * - `color` defaults to [1, 1, 1], `intensity` to 1 (candela for point and spot, lux for
 *   directional), `spot.innerConeAngle` to 0 and `spot.outerConeAngle` to π/4, with
 *   0 ≤ inner < outer ≤ π/2 (inner = outer is accepted: the spec's reference falloff,
 *   punctual.ts, handles it); `range` > 0, point and spot only.
 * The colour's schema range is [0, 1]; any finite colour ≥ 0 is accepted.
 */
import { GltfError } from './errors.ts';
import type { Mat4 } from './transforms.ts';
import { describeValue, fail, indexValue, isObject, list, type Json } from './validate-values.ts';
import type { LightDesc, Vec3 } from '../scene/format/types.ts';

const EXTENSION = 'KHR_lights_punctual';
const TYPES = ['directional', 'point', 'spot'];
const ROOT = `extensions.${EXTENSION}`;

/** The file's light list (checked by checkPunctualLights), empty without the extension. */
function lightList(json: Json): Json[] {
  const ext = (json.extensions as Json | undefined)?.[EXTENSION] as Json | undefined;
  return ext === undefined ? [] : (ext.lights as Json[]);
}

function finiteNumber(
  o: Json,
  key: string,
  path: string,
  ok: (x: number) => boolean,
  rule: string,
): void {
  const v = o[key];
  if (v === undefined) return;
  if (typeof v !== 'number' || !Number.isFinite(v) || !ok(v))
    fail(`${path}.${key}`, `must be a finite number ${rule}, got ${describeValue(v)}`);
}

/**
 * Checks the extension's lights and the nodes' references to them. Run before the
 * document is parsed, so a bad light is our error, not the parser's.
 */
export function checkPunctualLights(json: Json): void {
  const extensions = json.extensions;
  const ext = isObject(extensions) ? extensions[EXTENSION] : undefined;
  let count = 0;
  if (ext !== undefined) {
    if (!isObject(ext)) fail(ROOT, `must be an object, got ${describeValue(ext)}`);
    if (ext.lights === undefined) fail(`${ROOT}.lights`, 'is required');
    const lights = list(ext, 'lights', `${ROOT}.lights`);
    count = lights.length;
    lights.forEach((l, i) => {
      const p = `${ROOT}.lights[${i}]`;
      if (l.type === undefined) fail(`${p}.type`, 'is required');
      if (typeof l.type !== 'string' || !TYPES.includes(l.type))
        fail(
          `${p}.type`,
          `must be one of "directional", "point", "spot", got ${describeValue(l.type)}`,
        );
      const c = l.color;
      if (
        c !== undefined &&
        !(
          Array.isArray(c) &&
          c.length === 3 &&
          c.every((x) => typeof x === 'number' && Number.isFinite(x) && x >= 0)
        )
      )
        fail(`${p}.color`, 'must be 3 finite numbers ≥ 0');
      finiteNumber(l, 'intensity', p, (x) => x >= 0, '≥ 0');
      const color = (c as number[] | undefined) ?? [1, 1, 1];
      if (!Number.isFinite(((l.intensity as number | undefined) ?? 1) * Math.max(...color)))
        fail(`${p}.intensity`, 'times the colour overflows the double range');
      finiteNumber(l, 'range', p, (x) => x > 0, '> 0');
      if (l.range !== undefined && l.type === 'directional')
        fail(`${p}.range`, 'is allowed only on point and spot lights');
      if (l.spot !== undefined) {
        if (!isObject(l.spot)) fail(`${p}.spot`, `must be an object, got ${describeValue(l.spot)}`);
        const s = l.spot;
        const sp = `${p}.spot`;
        finiteNumber(s, 'innerConeAngle', sp, (x) => x >= 0 && x < Math.PI / 2, 'in [0, π/2)');
        finiteNumber(s, 'outerConeAngle', sp, (x) => x > 0 && x <= Math.PI / 2, 'in (0, π/2]');
        const inner = (s.innerConeAngle as number | undefined) ?? 0;
        const outer = (s.outerConeAngle as number | undefined) ?? Math.PI / 4;
        if (inner > outer)
          fail(sp, `innerConeAngle (${inner}) must be less than outerConeAngle (${outer})`);
      }
    });
  }
  const nodes = (json.nodes as Json[] | undefined) ?? [];
  nodes.forEach((n, i) => {
    const e = n.extensions;
    const ref = isObject(e) ? e[EXTENSION] : undefined;
    if (ref === undefined) return;
    const p = `nodes[${i}].extensions.${EXTENSION}`;
    if (!isObject(ref)) fail(p, `must be an object, got ${describeValue(ref)}`);
    if (ref.light === undefined) fail(`${p}.light`, 'is required');
    indexValue(ref.light, `${p}.light`, count, `${ROOT}.lights`);
  });
}

/**
 * The light of node `n` (checked) at world matrix m, or null when it has none, or a
 * string saying why it is not used.
 */
export function nodeLight(json: Json, n: Json, m: Mat4): LightDesc | null | string {
  const e = n.extensions as Json | undefined;
  const ref = e?.[EXTENSION] as Json | undefined;
  if (ref === undefined) return null;
  const l = lightList(json)[ref.light as number];
  const type = l.type as LightDesc['type'];
  const position: Vec3 = [m[12], m[13], m[14]];
  // Local −z (column 2 of the column-major matrix, negated), made unit: the scale
  // turns it but does not weaken the light.
  const len = Math.hypot(m[8], m[9], m[10]);
  if (type !== 'point' && !(len > 0 && len < Infinity))
    return "its node's world matrix is singular, so the light has no direction";
  const direction: Vec3 = type === 'point' ? [0, 0, -1] : [-m[8] / len, -m[9] / len, -m[10] / len];
  if (type !== 'directional' && !position.every(Number.isFinite))
    throw new GltfError(`${EXTENSION}: a light's node is at a non-finite position`);
  const spot = (l.spot as Json | undefined) ?? {};
  const deg = 180 / Math.PI;
  return {
    type,
    position: type === 'directional' ? [0, 0, 0] : position,
    direction,
    color: ((l.color as number[] | undefined) ?? [1, 1, 1]).slice(0, 3) as Vec3,
    intensity: (l.intensity as number | undefined) ?? 1,
    innerConeAngle: ((spot.innerConeAngle as number | undefined) ?? 0) * deg,
    outerConeAngle: ((spot.outerConeAngle as number | undefined) ?? Math.PI / 4) * deg,
    range: (l.range as number | undefined) ?? null,
  };
}
