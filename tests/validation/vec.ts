/** Small 3-vector helpers for the scene generator and the analytic tests (plain arrays, tests only). */
export type Vec3 = [number, number, number];

export const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const mul = (a: Vec3, k: number): Vec3 => [a[0] * k, a[1] * k, a[2] * k];
export const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
export const length = (a: Vec3): number => Math.hypot(a[0], a[1], a[2]);
export const normalize = (a: Vec3): Vec3 => mul(a, 1 / length(a));

/** Any unit vector perpendicular to unit n (Duff et al. 2017 branchless frame). */
export function perpendicular(n: Vec3): Vec3 {
  const sign = n[2] >= 0 ? 1 : -1;
  const a = -1 / (sign + n[2]);
  const b = n[0] * n[1] * a;
  return [1 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]];
}

/** Rotation of v about unit axis k by angle θ (Rodrigues). */
export function rotate(v: Vec3, k: Vec3, theta: number): Vec3 {
  const c = Math.cos(theta);
  const s = Math.sin(theta);
  return add(add(mul(v, c), mul(cross(k, v), s)), mul(k, dot(k, v) * (1 - c)));
}

/** A similarity transform x ↦ scale · R x + offset (R a rotation about `axis`). */
export class Similarity {
  constructor(
    readonly scale: number,
    readonly axis: Vec3,
    readonly angle: number,
    readonly offset: Vec3,
  ) {}

  point(p: Vec3): Vec3 {
    return add(mul(rotate(p, this.axis, this.angle), this.scale), this.offset);
  }

  /** A vector (edge, displacement): rotated and scaled, not translated. */
  vector(v: Vec3): Vec3 {
    return mul(rotate(v, this.axis, this.angle), this.scale);
  }

  /** A direction: rotated only. */
  direction(v: Vec3): Vec3 {
    return rotate(v, this.axis, this.angle);
  }
}
