/**
 * The glTF vertex attributes at a point of a triangle, interpolated
 * barycentrically into the caller's HitAttributes (texture coordinates and
 * vertex colour) for fillGltfShading, and the tangent for normal mapping.
 * Allocation-free; absent arrays give glTF's defaults (0 for texture
 * coordinates, white for the colour, no tangent).
 */
import type { HitAttributes } from './shading-fill.ts';

/** Per-vertex arrays of one set of triangles (GltfGeometry's, or the compiled scene's). */
export interface VertexAttributes {
  uv0: Float32Array | null;
  uv1: Float32Array | null;
  colors: Float32Array | null;
  tangents: Float32Array | null;
}

/**
 * Attributes at barycentrics (b1, b2) of the triangle with vertices i0, i1,
 * i2 (b0 = 1 − b1 − b2).
 */
export function interpolateAttributes(
  a: VertexAttributes,
  i0: number,
  i1: number,
  i2: number,
  b1: number,
  b2: number,
  out: HitAttributes,
): void {
  const b0 = 1 - b1 - b2;
  const uv0 = a.uv0;
  if (uv0 !== null) {
    out.u0 = b0 * uv0[2 * i0] + b1 * uv0[2 * i1] + b2 * uv0[2 * i2];
    out.v0 = b0 * uv0[2 * i0 + 1] + b1 * uv0[2 * i1 + 1] + b2 * uv0[2 * i2 + 1];
  } else {
    out.u0 = 0;
    out.v0 = 0;
  }
  const uv1 = a.uv1;
  if (uv1 !== null) {
    out.u1 = b0 * uv1[2 * i0] + b1 * uv1[2 * i1] + b2 * uv1[2 * i2];
    out.v1 = b0 * uv1[2 * i0 + 1] + b1 * uv1[2 * i1 + 1] + b2 * uv1[2 * i2 + 1];
  } else {
    out.u1 = 0;
    out.v1 = 0;
  }
  const c = a.colors;
  if (c !== null) {
    out.r = b0 * c[4 * i0] + b1 * c[4 * i1] + b2 * c[4 * i2];
    out.g = b0 * c[4 * i0 + 1] + b1 * c[4 * i1 + 1] + b2 * c[4 * i2 + 1];
    out.b = b0 * c[4 * i0 + 2] + b1 * c[4 * i1 + 2] + b2 * c[4 * i2 + 2];
    out.a = b0 * c[4 * i0 + 3] + b1 * c[4 * i1 + 3] + b2 * c[4 * i2 + 3];
  } else {
    out.r = 1;
    out.g = 1;
    out.b = 1;
    out.a = 1;
  }
}

/** Interpolated tangent (x, y, z, w) into out[0..3]; w is the first vertex's handedness. */
export function interpolateTangent(
  tangents: Float32Array,
  i0: number,
  i1: number,
  i2: number,
  b1: number,
  b2: number,
  out: Float64Array,
): void {
  const b0 = 1 - b1 - b2;
  for (let k = 0; k < 3; k++) {
    out[k] = b0 * tangents[4 * i0 + k] + b1 * tangents[4 * i1 + k] + b2 * tangents[4 * i2 + k];
  }
  // Handedness is constant over a triangle (MikkTSpace splits vertices where it changes).
  out[3] = tangents[4 * i0 + 3];
}
