/**
 * A random punctual light for the generated scenes (generate.ts): one draw of the
 * suite's seeded stream (rng.ts) gives a point, spot or directional light of
 * KHR_lights_punctual — its glTF definition (radians, candela or lux) and the node
 * placement that aims it — and the same light in the scene format's `lights` (degrees,
 * world space), so a family can put it in a glTF file or in a scene and expect one
 * picture.
 *
 * Its strength is drawn so that the irradiance it gives at `target` (point, spot: at
 * distance d, I = E·d²) is log-uniform in [0.3, 3] lux, the range of the generator's
 * emitters, whatever its distance; a spot is aimed at `target` (a random 0–0.6 of its
 * outer cone off it, so the target is sometimes in the falloff), a directional light
 * comes from above.
 */
import type { Rng } from './rng.ts';
import { cross, dot, length, normalize, sub, type Vec3 } from './vec.ts';

export type PunctualType = 'point' | 'spot' | 'directional';

/** KHR_lights_punctual's light object. */
export interface GltfPunctualLight {
  type: PunctualType;
  color: Vec3;
  intensity: number;
  spot?: { innerConeAngle: number; outerConeAngle: number };
}

export interface DrawnPunctualLight {
  gltf: GltfPunctualLight;
  /** The node holding it: translation and unit quaternion [x, y, z, w] turning −z onto its direction. */
  placement: { translation: Vec3; rotation: [number, number, number, number] };
  /** The same light as an entry of the scene format's `lights`. */
  scene: Record<string, unknown>;
}

/** The unit quaternion turning −z onto the unit vector d (shortest arc). */
export function quaternionFromMinusZ(d: Vec3): [number, number, number, number] {
  const from: Vec3 = [0, 0, -1];
  const c = dot(from, d);
  if (c < -1 + 1e-12) return [0, 1, 0, 0]; // d = +z: half a turn about y
  const axis = cross(from, d);
  // q = (axis, 1 + c) normalised: the half-angle form without trigonometry.
  const w = 1 + c;
  const n = Math.hypot(axis[0], axis[1], axis[2], w);
  return [axis[0] / n, axis[1] / n, axis[2] / n, w / n];
}

/**
 * A random punctual light lighting `target` from about `distance` away (point, spot);
 * `types` limits the kinds drawn.
 */
export function drawPunctualLight(
  rng: Rng,
  target: Vec3 = [0, 0, 0],
  distance = 2,
  types: readonly PunctualType[] = ['point', 'spot', 'directional'],
): DrawnPunctualLight {
  const type = rng.pick(types);
  const color: Vec3 = [rng.uniform(0.3, 1), rng.uniform(0.3, 1), rng.uniform(0.3, 1)];
  const irradiance = rng.logUniform(0.3, 3);
  // Above the target: a direction in the upper hemisphere, at least 15° over the horizon.
  const r = rng.direction();
  const up = normalize([r[0], Math.max(Math.abs(r[1]), 0.3), r[2]]);
  const d = distance * rng.uniform(0.75, 1.5);
  const position: Vec3 = [target[0] + up[0] * d, target[1] + up[1] * d, target[2] + up[2] * d];
  if (type === 'directional') {
    const direction: Vec3 = [-up[0], -up[1], -up[2]];
    return {
      gltf: { type, color, intensity: irradiance },
      placement: { translation: [0, 0, 0], rotation: quaternionFromMinusZ(direction) },
      scene: { type, direction, intensity: irradiance, color },
    };
  }
  const intensity = irradiance * d * d;
  if (type === 'point') {
    return {
      gltf: { type, color, intensity },
      placement: { translation: position, rotation: [0, 0, 0, 1] },
      scene: { type, position, intensity, color },
    };
  }
  const outer = rng.uniform(10, 80);
  const inner = rng.chance(0.2) ? 0 : outer * rng.uniform(0, 0.9);
  // Aim near the target: the axis turned a little off the line to it.
  const toTarget = normalize(sub(target, position));
  const off = ((rng.uniform(0, 0.6) * outer) / 180) * Math.PI;
  const across = cross(toTarget, rng.direction());
  const side = length(across) > 0 ? normalize(across) : across;
  const axis =
    length(side) > 0
      ? normalize([
          toTarget[0] * Math.cos(off) + side[0] * Math.sin(off),
          toTarget[1] * Math.cos(off) + side[1] * Math.sin(off),
          toTarget[2] * Math.cos(off) + side[2] * Math.sin(off),
        ])
      : toTarget;
  const rad = Math.PI / 180;
  return {
    gltf: {
      type,
      color,
      intensity,
      spot: { innerConeAngle: inner * rad, outerConeAngle: outer * rad },
    },
    placement: { translation: position, rotation: quaternionFromMinusZ(axis) },
    scene: {
      type,
      position,
      direction: axis,
      intensity,
      color,
      innerConeAngle: inner,
      outerConeAngle: outer,
    },
  };
}
