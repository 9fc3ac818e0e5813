/**
 * What the ray queries (trace.ts, traverse.ts) read of a compiled scene: the shapes'
 * arrays, the BVH and the per-scene scratch. The compiled scene (scene/compile/)
 * implements it; declaring it here keeps the queries below the compiler, which builds
 * the BVH they traverse, so the core's folders import only downward.
 */
import type { QuadList } from '../geometry/quad-list.ts';
import type { TriangleHit, TriangleRay } from '../geometry/triangle.ts';
import type { Bvh } from './bvh.ts';

export interface SceneGeometry {
  readonly sphereCount: number;
  readonly spheres: Float64Array;
  readonly quadCount: number;
  readonly quads: Float64Array;
  /** The quads regrouped for the plain loops; empty when the scene has a BVH. */
  readonly quadList: QuadList;
  readonly triCount: number;
  readonly triPositions: Float64Array;
  readonly triIndices: Int32Array;
  /** Per-ray constants of the triangle test and the barycentrics of the kept hit. */
  readonly triRay: TriangleRay;
  readonly triHit: TriangleHit;
  readonly bvh: Bvh | null;
  /** Traversal stack, sized for the BVH's depth, and the ray record (per scene object). */
  readonly stack: Int32Array;
  readonly stackT: Float64Array;
  readonly ray: Float64Array;
  /**
   * Instances (accel/instances.ts): their count, world-to-object matrices and BLAS root
   * nodes; the BLASes' nodes (as boxes and as words) and references; the BLAS stack and
   * the object-space ray record and triangle constants. Empty without instances.
   */
  readonly instanceCount: number;
  readonly instXform: Float64Array;
  readonly instBlas: Int32Array;
  readonly blasBoxes: Float32Array;
  readonly blasNodes: Int32Array;
  readonly blasRefs: Int32Array;
  readonly blasStack: Int32Array;
  readonly blasStackT: Float64Array;
  readonly objRay: Float64Array;
  readonly objTriRay: TriangleRay;
}
