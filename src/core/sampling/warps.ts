/**
 * Sampling warps: maps from the unit square to directions or points, each
 * with its density and, where it is a bijection, its inverse (pbr-book 4e,
 * §A.5 "Sampling Multidimensional Functions"). They come in threes so the
 * tests can check that `inverse(warp(u)) == u` and that each pdf integrates
 * to one. All write into a caller-owned `Vec3Out` so hot loops allocate
 * nothing.
 */

export interface Vec3Out {
  x: number;
  y: number;
  z: number;
}

export interface Vec2Out {
  x: number;
  y: number;
}

const PI = Math.PI;
const INV_PI = 1 / Math.PI;
const PI_OVER_4 = Math.PI / 4;
const PI_OVER_2 = Math.PI / 2;

/** Shirley–Chiu concentric map from [0,1)² to the unit disk (pbr-book 4e §A.5.1). */
export function squareToUniformDiskConcentric(u0: number, u1: number, out: Vec2Out): void {
  const ox = 2 * u0 - 1;
  const oy = 2 * u1 - 1;
  if (ox === 0 && oy === 0) {
    out.x = 0;
    out.y = 0;
    return;
  }
  let r: number;
  let theta: number;
  if (Math.abs(ox) > Math.abs(oy)) {
    r = ox;
    theta = PI_OVER_4 * (oy / ox);
  } else {
    r = oy;
    theta = PI_OVER_2 - PI_OVER_4 * (ox / oy);
  }
  out.x = r * Math.cos(theta);
  out.y = r * Math.sin(theta);
}

export function squareToUniformDiskConcentricPdf(x: number, y: number): number {
  return x * x + y * y <= 1 ? INV_PI : 0;
}

/** Inverse of the concentric map (pbr-book 4e §A.5.1, InvertUniformDiskConcentricSample). */
export function uniformDiskConcentricToSquare(x: number, y: number, out: Vec2Out): void {
  const theta = Math.atan2(y, x);
  const r = Math.sqrt(x * x + y * y);
  let ox: number;
  let oy: number;
  // Which wedge of the square the point came from, by its angle.
  if (Math.abs(theta) <= PI_OVER_4 || Math.abs(theta) >= 3 * PI_OVER_4) {
    ox = x >= 0 ? r : -r;
    // theta = PI/4 * oy/ox, with theta measured in the half plane of ox.
    const t = x >= 0 ? theta : theta > 0 ? theta - PI : theta + PI;
    oy = (ox * t) / PI_OVER_4;
  } else {
    oy = y >= 0 ? r : -r;
    const t = y >= 0 ? theta : theta + PI;
    ox = (oy * (PI_OVER_2 - t)) / PI_OVER_4;
  }
  out.x = (ox + 1) / 2;
  out.y = (oy + 1) / 2;
}

/** Cosine-weighted hemisphere around +z by Malley's method (pbr-book 4e §A.5.3). */
export function squareToCosineHemisphere(u0: number, u1: number, out: Vec3Out): void {
  const d = DISK;
  squareToUniformDiskConcentric(u0, u1, d);
  out.x = d.x;
  out.y = d.y;
  out.z = Math.sqrt(Math.max(0, 1 - d.x * d.x - d.y * d.y));
}
const DISK: Vec2Out = { x: 0, y: 0 };

export function squareToCosineHemispherePdf(z: number): number {
  return z > 0 ? z * INV_PI : 0;
}

export function cosineHemisphereToSquare(x: number, y: number, out: Vec2Out): void {
  uniformDiskConcentricToSquare(x, y, out);
}

/** Uniform direction on the unit sphere (pbr-book 4e §A.5.2). */
export function squareToUniformSphere(u0: number, u1: number, out: Vec3Out): void {
  const z = 1 - 2 * u0;
  const r = Math.sqrt(Math.max(0, 1 - z * z));
  const phi = 2 * PI * u1;
  out.x = r * Math.cos(phi);
  out.y = r * Math.sin(phi);
  out.z = z;
}

export function squareToUniformSpherePdf(): number {
  return 1 / (4 * PI);
}

export function uniformSphereToSquare(x: number, y: number, z: number, out: Vec2Out): void {
  out.x = (1 - z) / 2;
  let phi = Math.atan2(y, x);
  if (phi < 0) phi += 2 * PI;
  out.y = phi / (2 * PI);
}

/**
 * Uniform direction in the cone of half-angle acos(cosThetaMax) around +z
 * (pbr-book 4e §A.5.4). Used to sample a spherical light from outside.
 */
export function squareToUniformCone(
  u0: number,
  u1: number,
  cosThetaMax: number,
  out: Vec3Out,
): void {
  const cosTheta = 1 - u0 * (1 - cosThetaMax);
  const sinTheta = Math.sqrt(Math.max(0, 1 - cosTheta * cosTheta));
  const phi = 2 * PI * u1;
  out.x = sinTheta * Math.cos(phi);
  out.y = sinTheta * Math.sin(phi);
  out.z = cosTheta;
}

export function squareToUniformConePdf(cosThetaMax: number): number {
  return 1 / (2 * PI * (1 - cosThetaMax));
}

export function uniformConeToSquare(
  x: number,
  y: number,
  z: number,
  cosThetaMax: number,
  out: Vec2Out,
): void {
  out.x = (1 - z) / (1 - cosThetaMax);
  let phi = Math.atan2(y, x);
  if (phi < 0) phi += 2 * PI;
  out.y = phi / (2 * PI);
}

/**
 * Uniform point on a triangle as barycentrics (b0, b1), b2 = 1 − b0 − b1: the
 * low-distortion map of Heitz, "A Low-Distortion Map Between Triangle and Square"
 * (2019), as pbr-book 4e §A.5.5 uses it. out.x = b0, out.y = b1.
 */
export function squareToUniformTriangle(u0: number, u1: number, out: Vec2Out): void {
  if (u0 < u1) {
    out.x = u0 / 2;
    out.y = u1 - out.x;
  } else {
    out.y = u1 / 2;
    out.x = u0 - out.y;
  }
}

/** Density over the barycentric triangle (area 1/2); by area on a triangle it is 1/area. */
export function squareToUniformTrianglePdf(b0: number, b1: number): number {
  return b0 >= 0 && b1 >= 0 && b0 + b1 <= 1 ? 2 : 0;
}

export function uniformTriangleToSquare(b0: number, b1: number, out: Vec2Out): void {
  if (b0 > b1) {
    // From the branch u0 ≥ u1: b1 = u1 / 2, b0 = u0 − b1.
    out.y = 2 * b1;
    out.x = b0 + b1;
  } else {
    // From the branch u0 < u1: b0 = u0 / 2, b1 = u1 − b0.
    out.x = 2 * b0;
    out.y = b1 + b0;
  }
}
