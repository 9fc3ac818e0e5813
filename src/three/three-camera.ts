/**
 * A three.js PerspectiveCamera as pathwise's camera: the eye, its −z axis as forward
 * and its y axis as up (three's camera convention), the vertical field of view narrowed
 * by `zoom` as three's projection does. Depth of field comes from three-gpu-pathtracer's
 * PhysicalCamera where given: its bokeh size is the lens diameter in millimetres
 * (camera_util_functions.glsl: radius = bokehSize · 0.5e-3 scene units).
 */
import type { ThreeCamera } from './three-shapes.ts';
import { axis, translation, type Vec } from './three-lights.ts';

export interface SceneCamera {
  position: Vec;
  target: Vec;
  up: Vec;
  fovY: number;
  aperture?: number;
  focusDistance?: number;
}

export function convertCamera(camera: ThreeCamera, warn: (m: string) => void): SceneCamera {
  if (!camera?.isPerspectiveCamera) {
    throw new Error(
      'fromThree: the camera must be a PerspectiveCamera (pathwise has no orthographic camera)',
    );
  }
  camera.updateWorldMatrix(true, false);
  const position = translation(camera.matrixWorld);
  const z = axis(camera.matrixWorld, 2);
  const len = Math.hypot(z[0], z[1], z[2]);
  const forward: Vec = [-z[0] / len, -z[1] / len, -z[2] / len];
  const up = axis(camera.matrixWorld, 1);
  const zoom = camera.zoom > 0 ? camera.zoom : 1;
  const fovY = (2 * Math.atan(Math.tan((camera.fov * Math.PI) / 360) / zoom) * 180) / Math.PI;
  if (camera.view?.enabled || (camera.filmOffset ?? 0) !== 0) {
    warn('camera: view offset and filmOffset are not supported; the centred frustum is used');
  }
  const out: SceneCamera = { position, target: position, up, fovY };
  let distance = 1;
  const bokeh = camera.bokehSize ?? 0;
  if (typeof camera.fStop === 'number' && bokeh > 0 && (camera.focusDistance ?? 0) > 0) {
    distance = camera.focusDistance!;
    out.aperture = bokeh * 0.5e-3;
    out.focusDistance = distance;
  }
  out.target = [
    position[0] + forward[0] * distance,
    position[1] + forward[1] * distance,
    position[2] + forward[2] * distance,
  ];
  return out;
}
