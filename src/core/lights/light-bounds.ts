/**
 * Bounds on where a group of emitters is and which way it emits, and the importance
 * of such a group to a reference point: the building block of the light BVH
 * (light-bvh.ts). After pbrt-v4's `LightBounds` (pbr-book 4e §12.6.3, "Light Bounds";
 * Conty Estevez and Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree
 * Splitting"):
 * - an axis-aligned box around the emitters;
 * - phi, their power (the selection weights of lights.ts, relative to the largest);
 * - a cone of normals (axis w, half-angle θo) and the angle θe beyond the normals
 *   past which nothing is emitted (π/2 for area lights).
 *
 * Records are LB_STRIDE numbers in a Float64Array, so the BVH's nodes sit in one typed
 * array and the traversal allocates nothing.
 */

export const LB_STRIDE = 12;
/** Box corners. */
export const LB_MIN = 0;
export const LB_MAX = 3;
/** Unit axis of the cone of normals. */
export const LB_W = 6;
export const LB_PHI = 9;
export const LB_COS_O = 10;
export const LB_COS_E = 11;

/** Writes record `o` of `b`. */
export function setBounds(
  b: Float64Array,
  o: number,
  min: ArrayLike<number>,
  max: ArrayLike<number>,
  w: ArrayLike<number>,
  phi: number,
  cosO: number,
  cosE: number,
): void {
  for (let k = 0; k < 3; k++) {
    b[o + LB_MIN + k] = min[k];
    b[o + LB_MAX + k] = max[k];
    b[o + LB_W + k] = w[k];
  }
  b[o + LB_PHI] = phi;
  b[o + LB_COS_O] = cosO;
  b[o + LB_COS_E] = cosE;
}

/** acos clamped to [−1, 1], so rounding past ±1 gives 0 or π rather than NaN. */
function safeAcos(c: number): number {
  return Math.acos(Math.min(1, Math.max(-1, c)));
}

/**
 * Record `o` of `out` becomes the union of records `a` of `ba` and `c` of `bc` (pbrt-v4
 * `Union(LightBounds, LightBounds)` and `Union(DirectionCone, DirectionCone)`, pbr-book
 * 4e §3.8.4 "Bounding Directions"). A record of zero power is empty and adds nothing.
 */
export function unionBounds(
  ba: Float64Array,
  a: number,
  bc: Float64Array,
  c: number,
  out: Float64Array,
  o: number,
): void {
  if (!(ba[a + LB_PHI] > 0) && bc[c + LB_PHI] > 0) return copyBounds(bc, c, out, o);
  if (!(bc[c + LB_PHI] > 0)) return copyBounds(ba, a, out, o);
  const ax = ba[a + LB_W],
    ay = ba[a + LB_W + 1],
    az = ba[a + LB_W + 2];
  const bx = bc[c + LB_W],
    by = bc[c + LB_W + 1],
    bz = bc[c + LB_W + 2];
  const thetaA = safeAcos(ba[a + LB_COS_O]);
  const thetaB = safeAcos(bc[c + LB_COS_O]);
  // Angle between the axes from atan2 of |a × b| and a · b: exact for small angles.
  const cx = ay * bz - az * by,
    cy = az * bx - ax * bz,
    cz = ax * by - ay * bx;
  const crossLen = Math.sqrt(cx * cx + cy * cy + cz * cz);
  const thetaD = Math.atan2(crossLen, ax * bx + ay * by + az * bz);
  let wx: number, wy: number, wz: number, cosO: number;
  if (Math.min(thetaD + thetaB, Math.PI) <= thetaA) {
    wx = ax;
    wy = ay;
    wz = az;
    cosO = ba[a + LB_COS_O];
  } else if (Math.min(thetaD + thetaA, Math.PI) <= thetaB) {
    wx = bx;
    wy = by;
    wz = bz;
    cosO = bc[c + LB_COS_O];
  } else {
    const thetaO = (thetaA + thetaD + thetaB) / 2;
    if (thetaO >= Math.PI || crossLen === 0) {
      // The entire sphere.
      wx = 0;
      wy = 0;
      wz = 1;
      cosO = -1;
    } else {
      // Rotate a's axis toward b's by θo − θa about a × b (Rodrigues; the axis is
      // perpendicular to a, so two terms remain).
      const r = thetaO - thetaA;
      const kx = cx / crossLen,
        ky = cy / crossLen,
        kz = cz / crossLen;
      const cr = Math.cos(r),
        sr = Math.sin(r);
      wx = ax * cr + (ky * az - kz * ay) * sr;
      wy = ay * cr + (kz * ax - kx * az) * sr;
      wz = az * cr + (kx * ay - ky * ax) * sr;
      const len = Math.sqrt(wx * wx + wy * wy + wz * wz);
      wx /= len;
      wy /= len;
      wz /= len;
      cosO = Math.cos(thetaO);
    }
  }
  for (let k = 0; k < 3; k++) {
    out[o + LB_MIN + k] = Math.min(ba[a + LB_MIN + k], bc[c + LB_MIN + k]);
    out[o + LB_MAX + k] = Math.max(ba[a + LB_MAX + k], bc[c + LB_MAX + k]);
  }
  out[o + LB_W] = wx;
  out[o + LB_W + 1] = wy;
  out[o + LB_W + 2] = wz;
  out[o + LB_PHI] = ba[a + LB_PHI] + bc[c + LB_PHI];
  out[o + LB_COS_O] = cosO;
  out[o + LB_COS_E] = Math.min(ba[a + LB_COS_E], bc[c + LB_COS_E]);
}

export function copyBounds(b: Float64Array, a: number, out: Float64Array, o: number): void {
  for (let k = 0; k < LB_STRIDE; k++) out[o + k] = b[a + k];
}

/**
 * Numbers per record of `packBounds`' output, everything `importance` reads and nothing
 * else: the box's centre (IP_CENTRE, 3), its squared half-diagonal (IP_R2), the cone's
 * axis (IP_W, 3), phi, cos θo, sin θo and cos θe. One record is 96 bytes where the
 * bounds and what was derived from them took 136 in two arrays: the traversal of a large
 * light BVH waits on memory more than it computes (BENCHMARKS.md, many lights).
 */
export const IP_STRIDE = 12;
export const IP_CENTRE = 0;
export const IP_R2 = 3;
export const IP_W = 4;
export const IP_PHI = 7;
export const IP_COS_O = 8;
export const IP_SIN_O = 9;
export const IP_COS_E = 10;

/**
 * Record `o` of `b` packed for `importance` into record `od` of `d` (see IP_STRIDE): the
 * parts that do not depend on the point, computed once since the build's nodes are fixed.
 * Centre and half-diagonal as 0.5·lo + 0.5·hi: (lo + hi) / 2 would overflow for boxes
 * near the double range.
 */
export function packBounds(b: Float64Array, o: number, d: Float64Array, od: number): void {
  const x0 = b[o + LB_MIN],
    y0 = b[o + LB_MIN + 1],
    z0 = b[o + LB_MIN + 2];
  const x1 = b[o + LB_MAX],
    y1 = b[o + LB_MAX + 1],
    z1 = b[o + LB_MAX + 2];
  d[od + IP_CENTRE] = 0.5 * x0 + 0.5 * x1;
  d[od + IP_CENTRE + 1] = 0.5 * y0 + 0.5 * y1;
  d[od + IP_CENTRE + 2] = 0.5 * z0 + 0.5 * z1;
  const hx = 0.5 * x1 - 0.5 * x0,
    hy = 0.5 * y1 - 0.5 * y0,
    hz = 0.5 * z1 - 0.5 * z0;
  d[od + IP_R2] = hx * hx + hy * hy + hz * hz;
  d[od + IP_W] = b[o + LB_W];
  d[od + IP_W + 1] = b[o + LB_W + 1];
  d[od + IP_W + 2] = b[o + LB_W + 2];
  d[od + IP_PHI] = b[o + LB_PHI];
  const cosO = b[o + LB_COS_O];
  d[od + IP_COS_O] = cosO;
  d[od + IP_SIN_O] = Math.sqrt(Math.max(0, 1 - cosO * cosO));
  d[od + IP_COS_E] = b[o + LB_COS_E];
}

/**
 * The importance of packed record `o` of `d` (packBounds) to the point p = (x, y, z, nx,
 * ny, nz): (x, y, z) with surface normal (nx, ny, nz) (all zero: no surface). The
 * point comes in a typed array because a call V8 does not inline boxes each double
 * argument on the heap, and the light BVH makes dozens of these calls per vertex. pbrt-v4
 * `LightBounds::Importance`: phi × cos θ′ / d², where θ′ is the smallest angle the
 * emitters' normals can make with the direction to the point, and, at a surface,
 * × cos θ′ᵢ, the largest cosine the incident direction can make with its normal. 0 when
 * no emitter in the box can send light to the point.
 *
 * d² is the squared distance to the box's centre, clamped below by the squared
 * half-diagonal (pbrt clamps by the half-diagonal itself, which mixes units) so that
 * points inside a large box do not see it as infinitely important.
 */
export function importance(d: Float64Array, o: number, p: Float64Array): number {
  const phi = d[o + IP_PHI];
  if (!(phi > 0)) return 0;
  const nx = p[3],
    ny = p[4],
    nz = p[5];
  const r2 = d[o + IP_R2];
  let wx = p[0] - d[o + IP_CENTRE],
    wy = p[1] - d[o + IP_CENTRE + 1],
    wz = p[2] - d[o + IP_CENTRE + 2];
  const dist2 = wx * wx + wy * wy + wz * wz;
  const d2 = Math.max(dist2, r2);
  // The unit direction from the centre to the point (arbitrary at the centre itself).
  const dist = Math.sqrt(dist2);
  if (dist > 0) {
    wx /= dist;
    wy /= dist;
    wz /= dist;
  } else {
    wx = 0;
    wy = 0;
    wz = 1;
  }
  // θw: the angle between the cone's axis and that direction.
  const cosW = d[o + IP_W] * wx + d[o + IP_W + 1] * wy + d[o + IP_W + 2] * wz;
  const sinW = Math.sqrt(Math.max(0, 1 - cosW * cosW));
  // θb: half the angle the box subtends from the point, bounded by its bounding
  // sphere (pbrt-v4 BoundSubtendedDirections); the whole sphere from inside it. (The box
  // lies in the sphere, so a point inside the box is inside the sphere too.)
  let cosB = -1;
  if (dist2 > r2) cosB = Math.sqrt(Math.max(0, 1 - r2 / dist2));
  const sinB = Math.sqrt(Math.max(0, 1 - cosB * cosB));
  // θx = max(0, θw − θo), then θ′ = max(0, θx − θb), in cosines and sines (pbrt's
  // cosSubClamped and sinSubClamped).
  const cosO = d[o + IP_COS_O];
  const sinO = d[o + IP_SIN_O];
  let cosX: number, sinX: number;
  if (cosW > cosO) {
    cosX = 1;
    sinX = 0;
  } else {
    cosX = cosW * cosO + sinW * sinO;
    sinX = sinW * cosO - cosW * sinO;
  }
  const cosP = cosX > cosB ? 1 : cosX * cosB + sinX * sinB;
  if (cosP <= d[o + IP_COS_E]) return 0;
  let result = (phi * cosP) / d2;
  if (nx !== 0 || ny !== 0 || nz !== 0) {
    // θi: the angle between the normal and the direction to the centre, less θb.
    const cosI = Math.abs(wx * nx + wy * ny + wz * nz);
    const sinI = Math.sqrt(Math.max(0, 1 - cosI * cosI));
    result *= cosI > cosB ? 1 : cosI * cosB + sinI * sinB;
  }
  return result > 0 ? result : 0;
}

/**
 * The bounds' share of solid angle for the surface-area–orientation heuristic (pbrt-v4
 * `BVHLightSampler::EvaluateCost`, pbr-book 4e §12.6.3 eq. 12.24): the measure M_Ω of
 * the directions the emitters can emit into.
 */
export function orientationMeasure(b: Float64Array, o: number): number {
  const thetaO = safeAcos(b[o + LB_COS_O]);
  const thetaE = safeAcos(b[o + LB_COS_E]);
  const thetaW = Math.min(thetaO + thetaE, Math.PI);
  const sinO = Math.sin(thetaO);
  return (
    2 * Math.PI * (1 - Math.cos(thetaO)) +
    (Math.PI / 2) *
      (2 * thetaW * sinO - Math.cos(thetaO - 2 * thetaW) - 2 * thetaO * sinO + Math.cos(thetaO))
  );
}
