/**
 * A render in which the film accepted no sample at all is a failure, not a
 * picture: the film drops every sample that is not finite (film.ts), so a
 * scene whose numbers overflow somewhere downstream of the validator would
 * otherwise end as an all-black image with only a count of rejected samples.
 * This names the cause, for the command line's one line and the widget's
 * `error` event. The loader catches every overflow it can see (bounds,
 * transforms, framing); this is the last guard, so it says what it can find
 * and otherwise what it knows: every path's radiance was not finite.
 */
import { Camera } from '../camera/camera.ts';
import { Ray } from '../geometry/ray.ts';
import type { CameraDesc } from '../scene/format/types.ts';

/** True when a film that has finished at least one pass holds no accepted sample. */
export function filmIsEmpty(sums: Float32Array): boolean {
  // Index 4p + 3 is pixel p's count of accepted samples (film.ts).
  for (let i = 3; i < sums.length; i += 4) if (sums[i] !== 0) return false;
  return true;
}

/**
 * The line for a render whose `rejected` of `paths` samples were all left
 * out: what was dropped and, where it can be told from the camera, why.
 */
export function emptyImageMessage(
  camera: CameraDesc,
  width: number,
  height: number,
  rejected: number,
): string {
  return (
    `no image: all ${rejected} samples were not finite (or beyond ±2^40) and were left out; ` +
    emptyImageCause(camera, width, height)
  );
}

/** Why every sample was dropped, as far as the camera tells it. */
export function emptyImageCause(camera: CameraDesc, width: number, height: number): string {
  const cam = new Camera(camera, width, height);
  const frame = [cam.px, cam.py, cam.pz, cam.fx, cam.fy, cam.fz, cam.rx, cam.ry, cam.rz];
  if (!frame.every(Number.isFinite)) {
    return (
      'the camera has no finite frame (its position, target and up overflow double ' +
      'precision when combined)'
    );
  }
  // The rays through the four corners and the centre: a field of view or
  // a lens whose products overflow shows here.
  const ray = new Ray();
  for (const [x, y] of [
    [width / 2, height / 2],
    [0, 0],
    [width, 0],
    [0, height],
    [width, height],
  ]) {
    cam.generateRay(x, y, 0.5, 0.5, ray);
    const values = [ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz];
    // A direction whose square overflowed normalises to zero: finite, but no ray.
    const unit = Math.abs(Math.hypot(ray.dx, ray.dy, ray.dz) - 1) < 1e-9;
    if (!values.every(Number.isFinite) || !unit) {
      return `the camera's ray through film point (${x}, ${y}) is not finite`;
    }
  }
  return (
    "the camera's rays are finite, so every path's radiance was out of range: an emission, " +
    'a transform or an environment rotation in the scene is too large'
  );
}
