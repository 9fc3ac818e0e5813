/**
 * The scene's `camera` (docs/scene-format.md, Camera): position, target, up, fovY, and
 * an optional thin lens (aperture, focusDistance), checked so that the camera's frame
 * exists and its rays are finite (camera/camera.ts computes them).
 */
import type { CameraDesc } from '../format/types.ts';
import {
  NON_NEGATIVE,
  POSITIVE,
  cross,
  expectKnownKeys,
  expectNumber,
  expectObject,
  expectVec3,
  formatVec,
  length,
  normalize,
  sub,
  type Problems,
} from './validate-helpers.ts';

const CAMERA_KEYS = ['position', 'target', 'up', 'fovY', 'aperture', 'focusDistance'];

export function checkCamera(value: unknown, problems: Problems): CameraDesc | undefined {
  const obj = expectObject(value, 'camera', problems);
  if (obj === undefined) return undefined;
  const before = problems.length;
  expectKnownKeys(obj, 'camera', CAMERA_KEYS, problems);
  const position = expectVec3(obj.position, 'camera.position', problems);
  const target = expectVec3(obj.target, 'camera.target', problems);
  const up = expectVec3(obj.up, 'camera.up', problems);
  const fovY = expectNumber(obj.fovY, 'camera.fovY', problems, {
    ok: (x) => x > 0 && x < 180,
    rule: 'be in (0, 180) degrees',
  });
  const aperture =
    obj.aperture === undefined
      ? 0
      : expectNumber(obj.aperture, 'camera.aperture', problems, NON_NEGATIVE);
  const focus =
    obj.focusDistance === undefined
      ? undefined
      : expectNumber(obj.focusDistance, 'camera.focusDistance', problems, POSITIVE);

  // The frame (forward, right, upImage) must exist: forward needs position != target, and
  // right = normalize(cross(forward, up)) needs up non-zero and not parallel to forward.
  // Parallelism is tested on unit vectors, so it does not depend on the scene's scale.
  const upUnit = up === undefined ? undefined : normalize(up);
  if (up !== undefined && upUnit === undefined) {
    problems.push(`camera.up must be non-zero, got ${formatVec(up)}`);
  }
  let distance: number | undefined;
  if (position !== undefined && target !== undefined) {
    const forward = sub(target, position);
    distance = length(forward);
    if (distance === 0) {
      problems.push(
        `camera.target must differ from camera.position, both are ${formatVec(target)}`,
      );
    } else if (!Number.isFinite(distance)) {
      problems.push(`camera.target - camera.position must be finite, got ${formatVec(forward)}`);
    } else if (upUnit !== undefined && length(cross(normalize(forward)!, upUnit)) < 1e-6) {
      problems.push(
        `camera.up must not be parallel to camera.target - camera.position, got up ` +
          `${formatVec(up!)} and target - position ${formatVec(forward)}`,
      );
    }
  }
  if (problems.length === before && aperture! > 0) {
    // A thin lens (camera.ts) adds up to `aperture` to the position along right and up,
    // and aims at position + focusDistance·forward: each coordinate of either point, and
    // their difference, must stay finite, or the camera's rays are NaN and every sample
    // is dropped. Each value is finite alone; this is the sum the camera computes.
    const reach = focus ?? distance!;
    for (let a = 0; a < 3; a++) {
      const sum = Math.abs(position![a]) + aperture! + reach;
      if (!Number.isFinite(sum)) {
        problems.push(
          `camera.aperture ${aperture} and camera.focusDistance ${reach} reach beyond the double ` +
            `range from camera.position ${formatVec(position!)}: |position.${'xyz'[a]}| + aperture + focusDistance = ${sum}`,
        );
        break;
      }
    }
  }
  if (problems.length > before) return undefined;
  return {
    position: position!,
    target: target!,
    up: up!,
    fovY: fovY!,
    aperture: aperture!,
    focusDistance: focus ?? distance!,
  };
}
