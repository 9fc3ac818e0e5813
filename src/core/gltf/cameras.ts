/**
 * The cameras of a glTF scene in world space, for framing a bare model with
 * the file's own view (glTF 2.0 §3.10: a camera looks down its node's −z
 * with +y up; `yfov` is the full vertical field of view in radians).
 */
import type { GltfCamera } from '../scene/format/gltf-model.ts';
import type { Mat4 } from './transforms.ts';

type Json = Record<string, unknown>;

/**
 * A perspective camera at world matrix m, or why it is not used (validate.ts has
 * checked its numbers: yfov in (0, π), znear > 0).
 */
export function readCamera(cam: Json, m: Mat4): GltfCamera | string {
  const p = cam.perspective as Json | undefined;
  if (cam.type !== 'perspective' || p === undefined) return 'only perspective cameras are used';
  const yfov = ((p.yfov as number) * 180) / Math.PI;
  const position: [number, number, number] = [m[12], m[13], m[14]];
  // Cameras look down their local −z with +y up (glTF 2.0 §3.10).
  const fx = -m[8],
    fy = -m[9],
    fz = -m[10];
  const l = Math.hypot(fx, fy, fz);
  const ul = Math.hypot(m[4], m[5], m[6]);
  // A singular matrix (a scale of 0, or up mapped onto the view direction) leaves the
  // camera without a view direction or without a right vector.
  // (Unit vectors first: the products of a node scaled by 1e200 would overflow.)
  const [ax, ay, az] = [fx / l, fy / l, fz / l];
  const [bx, by, bz] = [m[4] / ul, m[5] / ul, m[6] / ul];
  const right = Math.hypot(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx);
  if (!(l > 0 && ul > 0 && right > 1e-9))
    return "its node's world matrix is singular, so it has no view direction and up";
  // The target a step along the view: a unit step is lost to rounding beyond ~1e16
  // (target = position, no direction at all), so the step grows with the position.
  const step = Math.max(
    1,
    Math.max(Math.abs(position[0]), Math.abs(position[1]), Math.abs(position[2])) * 2 ** -20,
  );
  const target: [number, number, number] = [
    position[0] + (fx / l) * step,
    position[1] + (fy / l) * step,
    position[2] + (fz / l) * step,
  ];
  if (!target.every(Number.isFinite))
    return `it is at (${position.join(', ')}) and looks out of the double range`;
  return {
    position,
    target,
    up: [m[4] / ul, m[5] / ul, m[6] / ul],
    fovY: yfov,
  };
}
