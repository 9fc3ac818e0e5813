/**
 * Orbit and dolly about the camera's target, as pure functions of a
 * CameraDesc. Orbiting turns the eye about the scene's up axis (azimuth)
 * and about the camera's right axis (elevation), keeping the distance; the
 * elevation stops short of the poles, where "up" would flip.
 */
import type { CameraDesc, Vec3 } from '../core/index.ts';

const MIN_POLAR = 0.02;

function normalize(v: Vec3): Vec3 {
  const l = Math.hypot(v[0], v[1], v[2]);
  return [v[0] / l, v[1] / l, v[2] / l];
}

function dot(a: Vec3, b: Vec3): number {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

function cross(a: Vec3, b: Vec3): Vec3 {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

/** Rodrigues' rotation of v about the unit axis k by angle a. */
function rotate(v: Vec3, k: Vec3, a: number): Vec3 {
  const c = Math.cos(a);
  const s = Math.sin(a);
  const kv = cross(k, v);
  const d = dot(k, v) * (1 - c);
  return [
    v[0] * c + kv[0] * s + k[0] * d,
    v[1] * c + kv[1] * s + k[1] * d,
    v[2] * c + kv[2] * s + k[2] * d,
  ];
}

/** Turns the eye by `yaw` radians about up and `pitch` radians about right. */
export function orbitCamera(camera: CameraDesc, yaw: number, pitch: number): CameraDesc {
  const up = normalize(camera.up);
  const t = camera.target;
  let offset: Vec3 = [
    camera.position[0] - t[0],
    camera.position[1] - t[1],
    camera.position[2] - t[2],
  ];
  const dist = Math.hypot(offset[0], offset[1], offset[2]);
  offset = rotate(offset, up, -yaw);
  // Clamp the pitch so the eye never crosses a pole.
  const polar = Math.acos(Math.max(-1, Math.min(1, dot(offset, up) / dist)));
  const newPolar = Math.max(MIN_POLAR, Math.min(Math.PI - MIN_POLAR, polar - pitch));
  const right = cross(offset, up);
  if (Math.hypot(right[0], right[1], right[2]) > 1e-12) {
    offset = rotate(offset, normalize(right), polar - newPolar);
  }
  return {
    ...camera,
    position: [t[0] + offset[0], t[1] + offset[1], t[2] + offset[2]],
  };
}

/**
 * Moves the eye toward (factor < 1) or away from the target. The focus
 * distance scales along, so what was in focus stays in focus.
 */
export function dollyCamera(camera: CameraDesc, factor: number): CameraDesc {
  const t = camera.target;
  const p = camera.position;
  const dist = Math.hypot(p[0] - t[0], p[1] - t[1], p[2] - t[2]);
  const f = Math.max(1e-3 / Math.max(dist, 1e-30), factor);
  return {
    ...camera,
    position: [t[0] + (p[0] - t[0]) * f, t[1] + (p[1] - t[1]) * f, t[2] + (p[2] - t[2]) * f],
    focusDistance: camera.focusDistance * f,
  };
}
