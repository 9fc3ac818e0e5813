/**
 * A triangle's two edges from its first vertex and their largest |component|: what a
 * triangle's area (lights/mesh-light.ts), its zero-area test (mesh-data.ts) and its
 * normal (written out in mesh-light.ts's triangleNormal) scale by before the cross
 * product, so that neither huge nor tiny triangles overflow or underflow into a false 0.
 */

/** Caller-owned result of triangleEdges. */
export class TriangleEdges {
  e1x = 0;
  e1y = 0;
  e1z = 0;
  e2x = 0;
  e2y = 0;
  e2z = 0;
  /** max |component| of e1 and e2: 0 for a point, Infinity when an edge overflows. */
  m = 0;
}

/**
 * e1 = p[b..b+2] − p[a..a+2], e2 = p[c..c+2] − p[a..a+2] (a, b, c: offsets of the
 * vertices' x in `p`) and their largest |component|, into `out`.
 */
export function triangleEdges(
  p: Float64Array,
  a: number,
  b: number,
  c: number,
  out: TriangleEdges,
): void {
  const e1x = p[b] - p[a],
    e1y = p[b + 1] - p[a + 1],
    e1z = p[b + 2] - p[a + 2];
  const e2x = p[c] - p[a],
    e2y = p[c + 1] - p[a + 1],
    e2z = p[c + 2] - p[a + 2];
  out.e1x = e1x;
  out.e1y = e1y;
  out.e1z = e1z;
  out.e2x = e2x;
  out.e2y = e2y;
  out.e2z = e2z;
  out.m = Math.max(
    Math.abs(e1x),
    Math.abs(e1y),
    Math.abs(e1z),
    Math.abs(e2x),
    Math.abs(e2y),
    Math.abs(e2z),
  );
}
