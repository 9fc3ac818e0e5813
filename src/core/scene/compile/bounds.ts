/**
 * The radius of a sphere around every shape of the scene (half the diagonal of their
 * bounding box): the environment map's power as an emitter is its radiance integral
 * times π r² of this sphere (pbr-book 4e §12.5.2, ImageInfiniteLight::Phi), so that it
 * competes fairly with the scene's area lights for light samples.
 */
import { QUAD_STRIDE, Q_CORNER, Q_U, Q_V, SPHERE_STRIDE } from '../../geometry/shapes.ts';

export function sceneRadius(
  spheres: Float64Array,
  sphereCount: number,
  quads: Float64Array,
  quadCount: number,
  positions: Float64Array,
  /** Instances' world boxes, six numbers each (accel/instances.ts). */
  boxes: Float64Array = new Float64Array(0),
): number {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  const add = (x: number, y: number, z: number, r: number) => {
    lo[0] = Math.min(lo[0], x - r);
    lo[1] = Math.min(lo[1], y - r);
    lo[2] = Math.min(lo[2], z - r);
    hi[0] = Math.max(hi[0], x + r);
    hi[1] = Math.max(hi[1], y + r);
    hi[2] = Math.max(hi[2], z + r);
  };
  for (let i = 0; i < sphereCount; i++) {
    const o = i * SPHERE_STRIDE;
    add(spheres[o], spheres[o + 1], spheres[o + 2], spheres[o + 3]);
  }
  for (let i = 0; i < quadCount; i++) {
    const o = i * QUAD_STRIDE;
    for (let k = 0; k < 4; k++) {
      const su = k & 1;
      const sv = k >> 1;
      add(
        quads[o + Q_CORNER] + su * quads[o + Q_U] + sv * quads[o + Q_V],
        quads[o + Q_CORNER + 1] + su * quads[o + Q_U + 1] + sv * quads[o + Q_V + 1],
        quads[o + Q_CORNER + 2] + su * quads[o + Q_U + 2] + sv * quads[o + Q_V + 2],
        0,
      );
    }
  }
  for (let i = 0; i < positions.length; i += 3) {
    add(positions[i], positions[i + 1], positions[i + 2], 0);
  }
  for (let i = 0; i < boxes.length; i += 6) {
    add(boxes[i], boxes[i + 1], boxes[i + 2], 0);
    add(boxes[i + 3], boxes[i + 4], boxes[i + 5], 0);
  }
  if (!(hi[0] >= lo[0])) return 0;
  return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2;
}
