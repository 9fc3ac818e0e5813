/**
 * The GGX (Trowbridge–Reitz) microfacet distribution (Walter et al., EGSR
 * 2007) with Smith masking, and Heitz's sampling of its visible normals
 * ("Sampling the GGX Distribution of Visible Normals", JCGT 2018). All in the
 * local frame, +z the macro-surface normal.
 */
import type { Vec3Out } from '../sampling/warps.ts';
import type { BsdfQuery } from './records.ts';

/** D(m) for a microfacet normal whose cosine with the normal is `cosThetaM`. */
export function ggxD(cosThetaM: number, alpha: number): number {
  if (cosThetaM <= 0) return 0;
  const a2 = alpha * alpha;
  const c2 = cosThetaM * cosThetaM;
  const d = c2 * (a2 - 1) + 1;
  return a2 / (Math.PI * d * d);
}

/**
 * Smith G1 for direction cosine z: 2 / (1 + sqrt(1 + α² tan²θ)), written as
 * 2z / (z + sqrt(z² + α²(1 − z²))) so that grazing directions (z → 0) give
 * 0 instead of 0/0.
 */
export function ggxG1(z: number, alpha: number): number {
  if (z <= 0) return 0;
  const z2 = z * z;
  return (2 * z) / (z + Math.sqrt(z2 + alpha * alpha * (1 - z2)));
}

/**
 * Samples a visible microfacet normal for the view direction q.wo (wo.z >
 * 0) from the unit square q.u0, q.u1 (Heitz 2018, listing 1), for the
 * roughness α = materials[alphaAt]. Writes the normal to `m`. Records in,
 * record out: when V8 does not inline the call, double arguments would be
 * boxed on the heap.
 */
export function ggxSampleVisibleNormal(
  q: BsdfQuery,
  materials: Float64Array,
  alphaAt: number,
  m: Vec3Out,
): void {
  const wox = q.wox,
    woy = q.woy,
    woz = q.woz,
    u0 = q.u0,
    u1 = q.u1;
  const alpha = materials[alphaAt];
  // Stretch the view direction into the hemisphere configuration.
  let vx = alpha * wox;
  let vy = alpha * woy;
  let vz = woz;
  const vl = 1 / Math.sqrt(vx * vx + vy * vy + vz * vz);
  vx *= vl;
  vy *= vl;
  vz *= vl;
  // Orthonormal basis around it (T1 is horizontal).
  const lensq = vx * vx + vy * vy;
  let t1x = 1;
  let t1y = 0;
  if (lensq > 0) {
    const inv = 1 / Math.sqrt(lensq);
    t1x = -vy * inv;
    t1y = vx * inv;
  }
  // T2 = V × T1 (T1 has no z component).
  const t2x = -vz * t1y;
  const t2y = vz * t1x;
  const t2z = vx * t1y - vy * t1x;
  // Uniform point on the projected disk, warped toward the visible half.
  const r = Math.sqrt(u0);
  const phi = 2 * Math.PI * u1;
  const p1 = r * Math.cos(phi);
  let p2 = r * Math.sin(phi);
  const s = 0.5 * (1 + vz);
  p2 = (1 - s) * Math.sqrt(Math.max(0, 1 - p1 * p1)) + s * p2;
  const p3 = Math.sqrt(Math.max(0, 1 - p1 * p1 - p2 * p2));
  const nx = p1 * t1x + p2 * t2x + p3 * vx;
  const ny = p1 * t1y + p2 * t2y + p3 * vy;
  const nz = p2 * t2z + p3 * vz;
  // Unstretch back to the ellipsoid configuration.
  let mx = alpha * nx;
  let my = alpha * ny;
  let mz = Math.max(0, nz);
  const ml = 1 / Math.sqrt(mx * mx + my * my + mz * mz);
  mx *= ml;
  my *= ml;
  mz *= ml;
  m.x = mx;
  m.y = my;
  m.z = mz;
}
