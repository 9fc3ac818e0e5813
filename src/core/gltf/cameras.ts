/**
 * The cameras of a glTF scene in world space, for framing a bare model with
 * the file's own view (glTF 2.0 §3.10: a camera looks down its node's −z
 * with +y up; `yfov` is the full vertical field of view in radians).
 */
import type { GltfCamera } from '../scene/format/gltf-model.ts';
import type { Mat4 } from './transforms.ts';

type Json = Record<string, unknown>;

/** A perspective camera at world matrix m, or null for an unusable one. */
export function readCamera(cam: Json, m: Mat4): GltfCamera | null {
  const p = cam.perspective as Json | undefined;
  if (cam.type !== 'perspective' || p === undefined || typeof p.yfov !== 'number') return null;
  const yfov = (p.yfov * 180) / Math.PI;
  if (!(yfov > 0 && yfov < 180)) return null;
  const position: [number, number, number] = [m[12], m[13], m[14]];
  // Cameras look down their local −z with +y up (glTF 2.0 §3.10).
  const fx = -m[8],
    fy = -m[9],
    fz = -m[10];
  const l = Math.hypot(fx, fy, fz);
  const ul = Math.hypot(m[4], m[5], m[6]);
  if (!(l > 0 && ul > 0)) return null;
  return {
    position,
    target: [position[0] + fx / l, position[1] + fy / l, position[2] + fz / l],
    up: [m[4] / ul, m[5] / ul, m[6] / ul],
    fovY: yfov,
  };
}
