/**
 * three.js lights as pathwise's: PointLight, SpotLight and DirectionalLight as the
 * scene's punctual `lights` (candela and lux, three's units since r155, which are
 * KHR_lights_punctual's and pathwise's), RectAreaLight as an emitting quad (its
 * `intensity` is luminance, nit, pathwise's radiance unit). Ambient and hemisphere
 * lights are a rasteriser's stand-in for indirect light, which the path tracer computes:
 * they are left out with a warning.
 */
import type { Mat4, ThreeObject } from './three-shapes.ts';
import { colorOf, numberOf } from './three-shapes.ts';

export type Vec = [number, number, number];

export interface SceneLight {
  type: 'point' | 'spot' | 'directional';
  position?: Vec;
  direction?: Vec;
  intensity: number;
  color: Vec;
  innerConeAngle?: number;
  outerConeAngle?: number;
}

export interface EmittingQuad {
  shape: { type: 'quad'; corner: Vec; u: Vec; v: Vec; material: string };
  material: { type: 'diffuse'; albedo: Vec; emission: Vec };
}

export function translation(m: Mat4): Vec {
  const e = m.elements;
  return [e[12], e[13], e[14]];
}

/** Column `c` (0–2) of the 3×3 part: a local axis in world space, with its scale. */
export function axis(m: Mat4, c: number): Vec {
  const e = m.elements;
  return [e[c * 4], e[c * 4 + 1], e[c * 4 + 2]];
}

const sub = (a: Vec, b: Vec): Vec => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const scale = (a: Vec, s: number): Vec => [a[0] * s, a[1] * s, a[2] * s];
const DEG = 180 / Math.PI;

/**
 * The light `o` as pathwise's, or null (after a warning) when it has none. `where`
 * names it in messages.
 */
export function convertLight(
  o: ThreeObject,
  where: string,
  warn: (m: string) => void,
): SceneLight | EmittingQuad | null {
  const color = colorOf(o, 'color') ?? [1, 1, 1];
  const intensity = numberOf(o, 'intensity', 1);
  const position = translation(o.matrixWorld);
  if (o.isPointLight || o.isSpotLight) {
    if (numberOf(o, 'decay', 2) !== 2) {
      warn(`${where}: decay ${String(o.decay)} is not physical; the inverse square law is used`);
    }
    if (numberOf(o, 'distance', 0) > 0) {
      warn(
        `${where}: distance ${String(o.distance)} cut-off ignored; the light reaches everywhere`,
      );
    }
  }
  if (o.isPointLight) return { type: 'point', position, intensity, color };
  if (o.isSpotLight || o.isDirectionalLight) {
    const target = o.target as ThreeObject | undefined;
    target?.updateWorldMatrix(true, false);
    const direction = sub(target ? translation(target.matrixWorld) : [0, 0, 0], position);
    if (direction[0] === 0 && direction[1] === 0 && direction[2] === 0) {
      warn(`${where}: its target is where it is; no direction, left out`);
      return null;
    }
    if (o.isDirectionalLight) return { type: 'directional', direction, intensity, color };
    if (o.map) warn(`${where}: the projected map is ignored`);
    const angle = numberOf(o, 'angle', Math.PI / 3);
    const penumbra = numberOf(o, 'penumbra', 0);
    // three fades with smoothstep between angle·(1 − penumbra) and angle; glTF's (and so
    // pathwise's) curve between the same cones is t² (docs/three.md).
    return {
      type: 'spot',
      position,
      direction,
      intensity,
      color,
      innerConeAngle: Math.min(89.999, angle * (1 - penumbra) * DEG),
      outerConeAngle: Math.min(90, angle * DEG),
    };
  }
  if (o.isRectAreaLight) {
    const w = numberOf(o, 'width', 10);
    const h = numberOf(o, 'height', 10);
    const x = axis(o.matrixWorld, 0);
    const y = axis(o.matrixWorld, 1);
    // It emits along its local −z (a light's lookAt turns −z to the target), one side,
    // so the quad's normal cross(u, v) must be −z: u along y, v along x.
    const corner = sub(sub(position, scale(x, w / 2)), scale(y, h / 2));
    return {
      shape: { type: 'quad', corner, u: scale(y, h), v: scale(x, w), material: '' },
      material: { type: 'diffuse', albedo: [0, 0, 0], emission: scale(color as Vec, intensity) },
    };
  }
  warn(
    `${where}: ${o.type ?? 'this light'} has no physical counterpart (the path tracer computes indirect light); left out`,
  );
  return null;
}
