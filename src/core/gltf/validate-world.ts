/**
 * What the node transforms make of a valid file, checked in world space
 * (glTF 2.0 §3.5.3: a world matrix is the product of the local matrices from
 * the root down). Every number of a file may be finite and the product still
 * not: a translation of 1.7e308 under a parent scaled by 10, a matrix of
 * diag(1e308) whose triangles' areas overflow, a quad moved to 1e308 where
 * doubles are 2e292 apart and all its corners round to one point. The
 * renderer would drop every sample of such a scene as non-finite, or render
 * the environment alone; here each is one message naming the node.
 */
import { GltfError } from './errors.ts';
import type { Mat4 } from './transforms.ts';

const AXES = ['x', 'y', 'z'];

/** The world matrix of nodes[node], refused when a product left the double range. */
export function checkWorldMatrix(m: Mat4, node: number, instance = -1): void {
  for (let k = 0; k < 16; k++) {
    if (!Number.isFinite(m[k])) {
      const what =
        k >= 12 ? `its world translation ${AXES[k - 12] ?? 'w'}` : `entry ${k} of its world matrix`;
      const of = instance < 0 ? '' : ` (EXT_mesh_gpu_instancing instance ${instance})`;
      throw new GltfError(
        `nodes[${node}]${of}: ${what} is ${m[k]}: the transforms of the node and its parents overflow the double range`,
      );
    }
  }
}

/** A world-space vertex that left the double range (finite input, finite matrix). */
export function vertexOverflow(
  node: number,
  where: string,
  vertex: number,
  p: ArrayLike<number>,
): GltfError {
  return new GltfError(
    `nodes[${node}]: vertex ${vertex} of ${where} is at (${p[0]}, ${p[1]}, ${p[2]}) in world space: ` +
      `the node's transforms take it beyond the double range`,
  );
}

/**
 * A triangle whose edges' cross product (twice its area) overflows in world space: its
 * normal and area are not numbers, and the renderer's intersection test (a cubic in the
 * coordinates, geometry/triangle.ts) cannot find it; it would vanish from the image.
 */
export function areaOverflow(node: number, where: string, triangle: number): GltfError {
  return new GltfError(
    `nodes[${node}]: triangle ${triangle} of ${where} has an area beyond the double range in world ` +
      `space: the node's transforms scale it too far for a ray to intersect it`,
  );
}

/**
 * An instance all of whose triangles lost their area to rounding in world space while
 * some have area in the primitive's own space: the node placed the mesh where doubles
 * are too far apart to tell its corners apart.
 */
export function collapsed(node: number, where: string, count: number, at: number): GltfError {
  const spacing = Math.abs(at) * Number.EPSILON;
  return new GltfError(
    `nodes[${node}]: all ${count} triangles of ${where} have zero area in world space: the node ` +
      `places them at ${at.toPrecision(3)}, where doubles are ${spacing.toPrecision(3)} apart`,
  );
}

/** Whether any triangle of `tris` has area in the primitive's own space. */
export function hasLocalArea(
  pos: Float32Array,
  tris: Uint32Array,
  source: Uint32Array | null,
): boolean {
  const s = (k: number): number => 3 * (source === null ? k : source[k]);
  for (let t = 0; t < tris.length; t += 3) {
    const a = s(tris[t]),
      b = s(tris[t + 1]),
      c = s(tris[t + 2]);
    const ex = pos[b] - pos[a],
      ey = pos[b + 1] - pos[a + 1],
      ez = pos[b + 2] - pos[a + 2];
    const fx = pos[c] - pos[a],
      fy = pos[c + 1] - pos[a + 1],
      fz = pos[c + 2] - pos[a + 2];
    if (ey * fz - ez * fy !== 0 || ez * fx - ex * fz !== 0 || ex * fy - ey * fx !== 0) return true;
  }
  return false;
}
