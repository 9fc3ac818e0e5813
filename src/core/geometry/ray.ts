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
  /** SHAPE_SPHERE or SHAPE_QUAD, or -1 for no hit. */
  kind = -1;
  index = -1;
}

export const SHAPE_SPHERE = 0;
export const SHAPE_QUAD = 1;
