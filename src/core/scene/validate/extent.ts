/**
 * The format's range rule (docs/scene-format.md, "Bad input"): every shape's bounds are
 * finite in double precision, and so is the extent of the whole scene (the difference
 * between its smallest and largest coordinate on each axis). Within these bounds any
 * magnitude is valid; beyond them a bounding box, a BVH split plane or a ray's distance
 * across the scene would be Infinity or NaN, so such a scene is refused at load with a
 * message naming the shape, never rendered as a black or empty picture.
 *
 * The check reads only what is loaded: a mesh or glTF shape whose file is not read yet is
 * skipped, and checked again by the loader once it is (files.ts, bare-scene.ts).
 */
import { triangleArea } from '../../lights/mesh-light.ts';
import { indexPath } from '../../util/message.ts';
import type { Scene, ShapeDesc } from '../format/types.ts';

const AXES = ['x', 'y', 'z'];

/** Bounds of the scene so far, with the shape that set each side. */
class Extent {
  readonly lo = [Infinity, Infinity, Infinity];
  readonly hi = [-Infinity, -Infinity, -Infinity];
  readonly loAt = ['', '', ''];
  readonly hiAt = ['', '', ''];

  add(x: number, y: number, z: number, at: string): void {
    this.side(0, x, at);
    this.side(1, y, at);
    this.side(2, z, at);
  }

  private side(a: number, v: number, at: string): void {
    if (v < this.lo[a]) {
      this.lo[a] = v;
      this.loAt[a] = at;
    }
    if (v > this.hi[a]) {
      this.hi[a] = v;
      this.hiAt[a] = at;
    }
  }
}

/** Whether a material of the scene's own emits. */
function emits(scene: Scene, material: string): boolean {
  const m = Object.hasOwn(scene.materials, material) ? scene.materials[material] : undefined;
  return m !== undefined && (m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0);
}

/**
 * An emitter is chosen for light samples by its power, emission × area, and sampled with
 * a density of 1 / area: both need the area as a finite, non-zero double.
 */
function emitterProblem(scene: Scene, shape: ShapeDesc): string | undefined {
  if (shape.type === 'sphere' && emits(scene, shape.material)) {
    const area = 4 * Math.PI * shape.radius * shape.radius;
    if (!(area > 0 && area < Infinity)) {
      return `it emits, and its area 4πr² = ${area} in double precision (an emitter's area must be finite and non-zero)`;
    }
  }
  if (shape.type === 'mesh' && shape.data !== null && emits(scene, shape.material)) {
    const { positions, indices } = shape.data;
    let area = 0;
    for (let t = 0; t < indices.length / 3; t++) area += triangleArea(positions, indices, t);
    if (!(area > 0 && area < Infinity)) {
      return `it emits, and its area is ${area} in double precision (an emitter's area must be finite and non-zero)`;
    }
  }
  return undefined;
}

/** The first point of a shape that is not finite, described, or undefined. */
function shapeProblem(shape: ShapeDesc, extent: Extent, at: string): string | undefined {
  switch (shape.type) {
    case 'sphere': {
      const [x, y, z] = shape.center;
      const r = shape.radius;
      for (let a = 0; a < 3; a++) {
        const c = shape.center[a];
        if (!Number.isFinite(c + r)) return `center.${AXES[a]} + radius = ${c + r}`;
        if (!Number.isFinite(c - r)) return `center.${AXES[a]} - radius = ${c - r}`;
      }
      extent.add(x - r, y - r, z - r, at);
      extent.add(x + r, y + r, z + r, at);
      return undefined;
    }
    case 'quad': {
      // The corners as the BVH's boxes compute them (accel/primitives.ts).
      const { corner, u, v } = shape;
      for (let k = 0; k < 4; k++) {
        const su = k & 1;
        const sv = k >> 1;
        const x = corner[0] + su * u[0] + sv * v[0];
        const y = corner[1] + su * u[1] + sv * v[1];
        const z = corner[2] + su * u[2] + sv * v[2];
        if (!(Number.isFinite(x) && Number.isFinite(y) && Number.isFinite(z))) {
          const which = ['corner', 'corner + u', 'corner + v', 'corner + u + v'][k];
          return `${which} = (${x}, ${y}, ${z})`;
        }
        extent.add(x, y, z, at);
      }
      return undefined;
    }
    case 'mesh':
    case 'gltf': {
      if (shape.data === null) return undefined;
      const p = shape.data.positions;
      for (let i = 0; i < p.length; i += 3) {
        const x = p[i],
          y = p[i + 1],
          z = p[i + 2];
        if (!(Number.isFinite(x) && Number.isFinite(y) && Number.isFinite(z))) {
          return `vertex ${i / 3} is at (${x}, ${y}, ${z}) in the scene`;
        }
        extent.add(x, y, z, at);
      }
      return undefined;
    }
  }
}

/**
 * The first breach of the range rule in `scene`, as one message naming the shape
 * (`shapes[4] reaches beyond the double range: center.x + radius = Infinity`), or
 * undefined. `label` names a shape for messages (a bare model has its own words).
 */
export function sceneRangeProblem(
  scene: Scene,
  label: (index: number) => string = (i) => indexPath('shapes', i),
): string | undefined {
  const extent = new Extent();
  for (let i = 0; i < scene.shapes.length; i++) {
    const problem = shapeProblem(scene.shapes[i], extent, label(i));
    if (problem !== undefined) return `${label(i)} reaches beyond the double range: ${problem}`;
    const emitter = emitterProblem(scene, scene.shapes[i]);
    if (emitter !== undefined) return `${label(i)} cannot be a light: ${emitter}`;
  }
  for (let a = 0; a < 3; a++) {
    const span = extent.hi[a] - extent.lo[a];
    if (span === Infinity) {
      const { loAt, hiAt, lo, hi } = extent;
      const who = loAt[a] === hiAt[a] ? loAt[a] : `${loAt[a]} and ${hiAt[a]}`;
      return (
        `the scene's extent overflows the double range: ${who} reach from ${AXES[a]} = ` +
        `${lo[a]} to ${AXES[a]} = ${hi[a]}, a span of more than 1.8e308`
      );
    }
  }
  return undefined;
}
