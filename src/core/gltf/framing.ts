/**
 * The camera of a bare glTF model (a `.glb` given to the widget, the demo or
 * the command line without a scene file): the file's first perspective
 * camera when it has one, else a view of the model's bounding sphere from
 * the front (+z, glTF's forward-facing convention), a little above, with the
 * whole sphere inside the field of view at the image's aspect ratio.
 */
import type { CameraDesc } from '../scene/types.ts';
import type { GltfCamera } from './cameras.ts';

/** Default vertical field of view of a framed model, in degrees. */
export const FRAMING_FOV_Y = 40;

export function frameModel(
  bounds: Float64Array,
  cameras: GltfCamera[],
  aspect: number,
): CameraDesc {
  if (cameras.length > 0) {
    const c = cameras[0];
    return {
      position: c.position,
      target: c.target,
      up: c.up,
      fovY: c.fovY,
      aperture: 0,
      focusDistance: 1,
    };
  }
  const empty = !(bounds[3] >= bounds[0]);
  const cx = empty ? 0 : 0.5 * (bounds[0] + bounds[3]);
  const cy = empty ? 0 : 0.5 * (bounds[1] + bounds[4]);
  const cz = empty ? 0 : 0.5 * (bounds[2] + bounds[5]);
  const r = empty
    ? 1
    : Math.max(
        1e-6,
        0.5 * Math.hypot(bounds[3] - bounds[0], bounds[4] - bounds[1], bounds[5] - bounds[2]),
      );
  const half = ((FRAMING_FOV_Y / 2) * Math.PI) / 180;
  // The narrower of the vertical and horizontal half-angles must hold the sphere.
  const halfX = Math.atan(Math.tan(half) * aspect);
  const d = (r / Math.sin(Math.min(half, halfX))) * 1.05;
  // From the front and 20° above.
  const el = (20 * Math.PI) / 180;
  const position: [number, number, number] = [cx, cy + d * Math.sin(el), cz + d * Math.cos(el)];
  return {
    position,
    target: [cx, cy, cz],
    up: [0, 1, 0],
    fovY: FRAMING_FOV_Y,
    aperture: 0,
    focusDistance: d,
  };
}
