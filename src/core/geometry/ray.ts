/** A ray with a unit direction; `tMax` bounds the search (Infinity for none). */
export class Ray {
  ox = 0;
  oy = 0;
  oz = 0;
  dx = 0;
  dy = 0;
  dz = 1;
  tMax = Infinity;
}

/**
 * What an intersection query writes: the nearest hit's distance and shape.
 * The surface details (point, normal) are filled in afterwards by
 * `completeHit`, only for the hit that is kept.
 */
export class Hit {
  t = Infinity;
  /** SHAPE_SPHERE, SHAPE_QUAD or SHAPE_TRIANGLE, or -1 for no hit. */
  kind = -1;
  index = -1;
  /** Barycentrics of a triangle hit (of its vertices 0, 1, 2); set for triangles only. */
  b0 = 0;
  b1 = 0;
  b2 = 0;
  /**
   * The instance (accel/instances.ts) whose object-space triangle `index` was hit, or −1
   * for a world-space shape; written only by scenes with instances.
   */
  instance = -1;
}

export const SHAPE_SPHERE = 0;
export const SHAPE_QUAD = 1;
/** One triangle of a mesh; its index runs over all meshes' triangles (scene/compile/compile-meshes.ts). */
export const SHAPE_TRIANGLE = 2;
/** Not a shape: the environment map, as a kind of light (lights/lights.ts). */
export const LIGHT_ENVIRONMENT = 3;
/**
 * Not shapes either: the punctual (delta) lights of KHR_lights_punctual and the scene
 * format's `lights` (lights/punctual.ts). Every tag from LIGHT_POINT on is a delta light.
 */
export const LIGHT_POINT = 4;
export const LIGHT_SPOT = 5;
export const LIGHT_DIRECTIONAL = 6;

/**
 * Ray record layout (a Float64Array the queries of trace.ts fill): origin,
 * direction, far bound. Primitive tests read the ray from it and move R_T
 * to a closer hit; they take and return no double, which V8 would box
 * whenever it does not inline the call.
 */
export const R_OX = 0;
export const R_DX = 3;
export const R_T = 6;
export const RAY_RECORD_WORDS = 8;

/** Copies a ray into a ray record. */
export function loadRay(r: Float64Array, ray: Ray): void {
  r[0] = ray.ox;
  r[1] = ray.oy;
  r[2] = ray.oz;
  r[3] = ray.dx;
  r[4] = ray.dy;
  r[5] = ray.dz;
  r[6] = ray.tMax;
}
