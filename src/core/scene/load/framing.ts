/**
 * The camera of a bare glTF model (a `.glb` given to the widget, the demo or
 * the command line without a scene file): the file's first perspective
 * camera when it has one, else a view of the model's bounding sphere from
 * the front (+z, glTF's forward-facing convention), a little above, with the
 * whole sphere inside the field of view at the image's aspect ratio.
 */
import type { CameraDesc } from '../format/types.ts';
import type { GltfCamera } from '../format/gltf-model.ts';

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
  // Halves first: the sum of two bounds near the double range would overflow.
  const cx = empty ? 0 : 0.5 * bounds[0] + 0.5 * bounds[3];
  const cy = empty ? 0 : 0.5 * bounds[1] + 0.5 * bounds[4];
  const cz = empty ? 0 : 0.5 * bounds[2] + 0.5 * bounds[5];
  const radius = empty
    ? 1
    : Math.hypot(
        0.5 * (bounds[3] - bounds[0]),
        0.5 * (bounds[4] - bounds[1]),
        0.5 * (bounds[5] - bounds[2]),
      );
  // A model of one point gets a sphere in proportion to where it is.
  const r = radius > 0 ? radius : 1e-6 * Math.max(Math.abs(cx), Math.abs(cy), Math.abs(cz)) || 1e-6;
  const half = ((FRAMING_FOV_Y / 2) * Math.PI) / 180;
  // The narrower of the vertical and horizontal half-angles must hold the sphere.
  const halfX = Math.atan(Math.tan(half) * aspect);
  let d = Math.min((r / Math.sin(Math.min(half, halfX))) * 1.05, Number.MAX_VALUE);
  // From the front and 20° above. A model near the end of the double range is seen
  // from the side that has room (behind, below), and from nearer still if neither has:
  // the camera's position must be finite.
  const el = (20 * Math.PI) / 180;
  const sy = cy + d * Math.sin(el) < Infinity ? 1 : -1;
  const sz = cz + d * Math.cos(el) < Infinity ? 1 : -1;
  while (!(
    Number.isFinite(cy + sy * d * Math.sin(el)) && Number.isFinite(cz + sz * d * Math.cos(el))
  )) {
    d *= 0.5;
  }
  const position: [number, number, number] = [
    cx,
    cy + sy * d * Math.sin(el),
    cz + sz * d * Math.cos(el),
  ];
  return {
    position,
    target: [cx, cy, cz],
    up: [0, 1, 0],
    fovY: FRAMING_FOV_Y,
    aperture: 0,
    focusDistance: d,
  };
}
