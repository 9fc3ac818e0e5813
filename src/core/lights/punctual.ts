/**
 * Punctual lights — point, spot and directional (KHR_lights_punctual; the scene
 * format's `lights`) — as delta lights of next-event estimation (pbr-book 4e §12.1,
 * PointLight, SpotLight, DistantLight). Each has one direction toward any point,
 * so a light sample is that direction with the discrete probability of choosing the
 * light as its `pdf`; no BSDF-sampled ray can hit one, so its NEE sample takes MIS
 * weight 1 (trace-path.ts) and a delta BSDF lobe receives nothing from it.
 *
 * Units (KHR_lights_punctual, "Light Shared Properties"): point and spot intensity
 * in candela, directional in lux. pathwise's radiance is in nit (cd/m²), the unit
 * of emissive materials and environments, so no 683 lm/W factor enters:
 * - point, spot: the irradiance on a surface facing the light is I / d² (lux);
 * - directional: it is the intensity itself (lux).
 * The sample's r, g, b is that irradiance, colour × intensity × attenuation; the
 * integrator multiplies it by f · |cosθ| / pdf like an environment sample.
 *
 * Spot cone (the extension's "Inner and Outer Cone Angles" reference code):
 * t = saturate((cos θ − cos outer) · s), s = 1 / max(0.001, cos inner − cos outer),
 * attenuation t². `range` (point, spot): "rendering engines [must] ignore the light
 * beyond this range"; inside it the attenuation is the pure inverse square law, which
 * the spec asks to follow "as closely as possible" (its windowed falloff is optional
 * and is not applied), so the light stops at `range` with a hard edge.
 *
 * Selection weights (lights.ts chooses by power) are in the units of the area lights'
 * luminance × area, i.e. power / π: point 4·I, spot 2(1 − cos outer)·I (an upper
 * bound of its cone's power), directional E·R² with R the scene's bounding radius
 * (as the environment map's, compile.ts). I and E are the luminance of colour ×
 * intensity, floored like emitters' so a pure-blue light is still chosen.
 */
import { LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT } from '../geometry/ray.ts';
import type { LightDesc } from '../scene/format/types.ts';
import type { LightSample } from './lights.ts';

/** Numbers per light in the compiled array (SceneData.punctual). */
export const PUNCTUAL_STRIDE = 12;
/** World position (point, spot). */
export const P_POSITION = 0;
/** Unit direction the light travels (spot, directional). */
export const P_DIRECTION = 3;
/** colour × intensity: candela (point, spot) or lux (directional). */
export const P_INTENSITY = 6;
/** cos outerConeAngle and the cone's scale s (see the module comment). */
export const P_COS_OUTER = 9;
export const P_ANGLE_SCALE = 10;
/** Distance beyond which the light gives nothing; Infinity for none. */
export const P_RANGE = 11;

const DEG = Math.PI / 180;

/** The cone's scale s of the spec's reference code. */
export function spotAngleScale(cosInner: number, cosOuter: number): number {
  return 1 / Math.max(0.001, cosInner - cosOuter);
}

/** The spot's angular attenuation at cos θ from its axis (the spec's reference code). */
export function spotAttenuation(cosTheta: number, cosOuter: number, scale: number): number {
  const t = Math.min(1, Math.max(0, (cosTheta - cosOuter) * scale));
  return t * t;
}

export interface CompiledPunctual {
  /** PUNCTUAL_STRIDE numbers per light. */
  data: Float64Array;
  /** LIGHT_POINT, LIGHT_SPOT or LIGHT_DIRECTIONAL per light. */
  kinds: number[];
  /** Selection weight per light and its log2 (for light-power.ts selectionWeights). */
  power: number[];
  powerLog: number[];
}

/**
 * The lights that can give light (colour × intensity not black), in order.
 * `radius`: the scene's bounding radius, for directional lights' weights.
 */
export function compilePunctualLights(
  lights: readonly LightDesc[],
  radius: number,
): CompiledPunctual {
  const kept = lights.filter((l) => l.intensity * Math.max(...l.color) > 0);
  const data = new Float64Array(kept.length * PUNCTUAL_STRIDE);
  const kinds: number[] = [];
  const power: number[] = [];
  const powerLog: number[] = [];
  kept.forEach((l, i) => {
    const o = i * PUNCTUAL_STRIDE;
    data.set(l.position, o + P_POSITION);
    data.set(l.direction, o + P_DIRECTION);
    const r = l.color[0] * l.intensity;
    const g = l.color[1] * l.intensity;
    const b = l.color[2] * l.intensity;
    data[o + P_INTENSITY] = r;
    data[o + P_INTENSITY + 1] = g;
    data[o + P_INTENSITY + 2] = b;
    const cosOuter = Math.cos(l.outerConeAngle * DEG);
    data[o + P_COS_OUTER] = cosOuter;
    data[o + P_ANGLE_SCALE] = spotAngleScale(Math.cos(l.innerConeAngle * DEG), cosOuter);
    data[o + P_RANGE] = l.range ?? Infinity;
    const lum = Math.max(0.2126 * r + 0.7152 * g + 0.0722 * b, 1e-6 * Math.max(r, g, b));
    let factor: number;
    if (l.type === 'point') {
      kinds.push(LIGHT_POINT);
      factor = 4;
    } else if (l.type === 'spot') {
      kinds.push(LIGHT_SPOT);
      // 1 − cos outer without cancellation for narrow cones.
      const s = Math.sin((l.outerConeAngle * DEG) / 2);
      factor = 4 * s * s;
    } else {
      kinds.push(LIGHT_DIRECTIONAL);
      // A scene with no geometry: nothing to light, any positive weight will do.
      factor = radius > 0 ? radius * radius : 1;
    }
    power.push(lum * factor);
    powerLog.push(
      Math.log2(lum) +
        (l.type === 'directional' && radius > 0 ? 2 * Math.log2(radius) : Math.log2(factor)),
    );
  });
  return { data, kinds, power, powerLog };
}

/**
 * The sample of punctual light `index` (of kind `kind`) seen from (out.refX, refY,
 * refZ): the direction toward it, its distance (Infinity for a directional light) and
 * position, `pdf` = `choose` (the discrete probability of this light), and in r, g, b
 * the irradiance it gives a surface facing it. False when it gives nothing there
 * (outside the cone or the range, at the light itself).
 */
export function samplePunctual(
  data: Float64Array,
  index: number,
  kind: number,
  choose: number,
  out: LightSample,
): boolean {
  const o = index * PUNCTUAL_STRIDE;
  const dx = data[o + P_DIRECTION],
    dy = data[o + P_DIRECTION + 1],
    dz = data[o + P_DIRECTION + 2];
  out.pdf = choose;
  if (kind === LIGHT_DIRECTIONAL) {
    out.wx = -dx;
    out.wy = -dy;
    out.wz = -dz;
    out.distance = Infinity;
    out.r = data[o + P_INTENSITY];
    out.g = data[o + P_INTENSITY + 1];
    out.b = data[o + P_INTENSITY + 2];
    return true;
  }
  const px = data[o + P_POSITION],
    py = data[o + P_POSITION + 1],
    pz = data[o + P_POSITION + 2];
  let wx = px - out.refX;
  let wy = py - out.refY;
  let wz = pz - out.refZ;
  const d2 = wx * wx + wy * wy + wz * wz;
  // At the light itself, or so far (d > 1e154) that d² overflows and I / d² is 0.
  if (!(d2 > 0 && d2 < Infinity)) return false;
  const d = Math.sqrt(d2);
  if (d > data[o + P_RANGE]) return false;
  wx /= d;
  wy /= d;
  wz /= d;
  let attenuation = 1 / d2;
  if (kind === LIGHT_SPOT) {
    // θ between the spot's axis and the way the light leaves toward the point (−w).
    const cosTheta = -(wx * dx + wy * dy + wz * dz);
    const a = spotAttenuation(cosTheta, data[o + P_COS_OUTER], data[o + P_ANGLE_SCALE]);
    if (a === 0) return false;
    attenuation *= a;
  }
  const r = data[o + P_INTENSITY] * attenuation;
  const g = data[o + P_INTENSITY + 1] * attenuation;
  const b = data[o + P_INTENSITY + 2] * attenuation;
  // A point a hair from the light: I / d² overflows; such a sample is dropped, not
  // sent to the film as Infinity.
  if (!(r < Infinity && g < Infinity && b < Infinity)) return false;
  out.wx = wx;
  out.wy = wy;
  out.wz = wz;
  out.distance = d;
  // Nothing to lift the far end off: no surface is there.
  out.px = px;
  out.py = py;
  out.pz = pz;
  out.r = r;
  out.g = g;
  out.b = b;
  return true;
}
