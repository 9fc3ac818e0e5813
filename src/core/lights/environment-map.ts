/**
 * An equirectangular environment map as a light (docs/scene-format.md, Environment
 * maps): the radiance of a direction is the nearest texel, exactly as the spec writes
 * the lookup; directions are importance-sampled in proportion to luminance times solid
 * angle (pbr-book 4e §12.5.2 "Image Infinite Lights").
 *
 * The solid angle of a texel in row i is (2π / W)·(cos θᵢ − cos θᵢ₊₁), the integral of
 * sin θ over the row, and a direction is drawn uniformly in solid angle inside the
 * chosen texel (uniform in φ and in cos θ). The density is therefore constant inside a
 * texel and exactly proportional to the texel's luminance: luminance / pdf is the same
 * for every sample (the map's integral), which the tests check. pbrt's usual sin θ at
 * the texel centre, with the point uniform in (u, v), is only approximately so.
 *
 * `sample`, `pdf` and `invert` are the three faces of the warp (sample → direction,
 * its density, and back to the random numbers).
 */
import type { EnvironmentMapDesc } from '../scene/format/types.ts';
import { Distribution2D } from '../sampling/distribution.ts';
import type { Vec2Out } from '../sampling/warps.ts';

const TWO_PI = 2 * Math.PI;
const INV_TWO_PI = 1 / TWO_PI;
const INV_PI = 1 / Math.PI;

/** What `sample` writes: a world direction, its solid-angle pdf and the radiance. */
export class EnvironmentSample {
  wx = 0;
  wy = 0;
  wz = 1;
  pdf = 0;
  r = 0;
  g = 0;
  b = 0;
}

/** Relative luminance of linear Rec.709 RGB (ITU-R BT.709). */
export function luminance(r: number, g: number, b: number): number {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

export class EnvironmentMap {
  readonly width: number;
  readonly height: number;
  /** Texels without the scale, row 0 at the top (+y). */
  readonly rgb: Float32Array;
  readonly scaleR: number;
  readonly scaleG: number;
  readonly scaleB: number;
  readonly cosRot: number;
  readonly sinRot: number;
  /** cos θ at the top edge of each row (height + 1 entries, from 1 to −1). */
  readonly rowCos: Float64Array;
  /** cos θ(top) − cos θ(bottom) of each row: its solid angle is this times 2π / W. */
  readonly rowDelta: Float64Array;
  readonly distribution: Distribution2D;
  /** ∫ luminance dω over the sphere: the map's weight among the scene's emitters. */
  readonly integral: number;

  constructor(desc: EnvironmentMapDesc) {
    const image = desc.image;
    if (image === null) throw new Error('environment map: its image has not been read');
    const { width, height, rgb } = image;
    this.width = width;
    this.height = height;
    this.rgb = rgb;
    [this.scaleR, this.scaleG, this.scaleB] = desc.scale;
    // Whole turns first: any finite angle is valid, and 1e308 · π would overflow. The
    // remainder is exact, so angles within a turn are as before.
    const theta = ((desc.rotationY % 360) * Math.PI) / 180;
    this.cosRot = Math.cos(theta);
    this.sinRot = Math.sin(theta);
    this.rowCos = new Float64Array(height + 1);
    this.rowDelta = new Float64Array(height);
    for (let i = 0; i <= height; i++) this.rowCos[i] = Math.cos((Math.PI * i) / height);
    this.rowCos[0] = 1;
    this.rowCos[height] = -1;
    for (let i = 0; i < height; i++) {
      // cos a − cos b = 2 sin((a + b)/2) sin((b − a)/2): no cancellation near the poles.
      const a = (Math.PI * i) / height;
      const b = (Math.PI * (i + 1)) / height;
      this.rowDelta[i] = 2 * Math.sin((a + b) / 2) * Math.sin((b - a) / 2);
    }
    const sr = this.scaleR,
      sg = this.scaleG,
      sb = this.scaleB;
    this.distribution = new Distribution2D(width, height, (row, out) => {
      const d = this.rowDelta[row];
      for (let x = 0, o = row * width * 3; x < width; x++, o += 3) {
        out[x] = luminance(rgb[o] * sr, rgb[o + 1] * sg, rgb[o + 2] * sb) * d;
      }
    });
    this.integral = (this.distribution.total * TWO_PI) / width;
  }

  /** Index (row · W + column) of the texel seen along the unit world direction d. */
  texel(dx: number, dy: number, dz: number): number {
    const x = this.cosRot * dx - this.sinRot * dz;
    const z = this.sinRot * dx + this.cosRot * dz;
    let u = Math.atan2(x, -z) * INV_TWO_PI;
    u -= Math.floor(u);
    const v = Math.acos(dy > 1 ? 1 : dy < -1 ? -1 : dy) * INV_PI;
    const w = this.width,
      h = this.height;
    const col = Math.min(Math.floor(u * w), w - 1);
    const row = Math.min(Math.floor(v * h), h - 1);
    return row * w + col;
  }

  /** Radiance along d (scale applied) into out.r, g, b. */
  eval(dx: number, dy: number, dz: number, out: EnvironmentSample): void {
    const o = this.texel(dx, dy, dz) * 3;
    out.r = this.rgb[o] * this.scaleR;
    out.g = this.rgb[o + 1] * this.scaleG;
    out.b = this.rgb[o + 2] * this.scaleB;
  }

  /** Solid-angle density with which `sample` draws the unit world direction d. */
  pdf(dx: number, dy: number, dz: number): number {
    const t = this.texel(dx, dy, dz);
    const row = Math.floor(t / this.width);
    const p = this.distribution.prob(t - row * this.width, row);
    return p === 0 ? 0 : (p * this.width) / (TWO_PI * this.rowDelta[row]);
  }

  /**
   * Draws a direction with (u0, u1) ∈ [0, 1)²; writes it with its pdf and radiance.
   * Returns false when the map is black (nothing to sample).
   */
  sample(u0: number, u1: number, out: EnvironmentSample): boolean {
    if (!(this.integral > 0)) return false;
    const cell = CELL;
    this.distribution.sample(u0, u1, cell);
    const row = Math.min(this.height - 1, Math.floor(cell.y));
    const fy = cell.y - row;
    const cosTheta = this.rowCos[row] - fy * this.rowDelta[row];
    const sinTheta = Math.sqrt(Math.max(0, (1 - cosTheta) * (1 + cosTheta)));
    const phi = (TWO_PI * cell.x) / this.width;
    // Map space: atan2(x', −z') = φ, y' = cos θ.
    const xm = sinTheta * Math.sin(phi);
    const zm = -sinTheta * Math.cos(phi);
    // World = the inverse of the lookup's rotation about +y.
    const wx = this.cosRot * xm + this.sinRot * zm;
    const wz = -this.sinRot * xm + this.cosRot * zm;
    out.wx = wx;
    out.wy = cosTheta;
    out.wz = wz;
    // Density and radiance of the texel the lookup finds for this direction, so that
    // sample, pdf and eval agree even on a texel border.
    const t = this.texel(wx, cosTheta, wz);
    const trow = Math.floor(t / this.width);
    const p = this.distribution.prob(t - trow * this.width, trow);
    if (p === 0) return false;
    out.pdf = (p * this.width) / (TWO_PI * this.rowDelta[trow]);
    out.r = this.rgb[3 * t] * this.scaleR;
    out.g = this.rgb[3 * t + 1] * this.scaleG;
    out.b = this.rgb[3 * t + 2] * this.scaleB;
    return true;
  }

  /** The (u0, u1) that `sample` takes to the unit world direction d. */
  invert(dx: number, dy: number, dz: number, out: Vec2Out): void {
    const x = this.cosRot * dx - this.sinRot * dz;
    const z = this.sinRot * dx + this.cosRot * dz;
    let u = Math.atan2(x, -z) * INV_TWO_PI;
    u -= Math.floor(u);
    const y = dy > 1 ? 1 : dy < -1 ? -1 : dy;
    const v = Math.acos(y) * INV_PI;
    const row = Math.min(Math.floor(v * this.height), this.height - 1);
    const fy = Math.min(1, Math.max(0, (this.rowCos[row] - y) / this.rowDelta[row]));
    this.distribution.invert(Math.min(u * this.width, this.width - 1e-9), row + fy, out);
  }
}

const CELL: Vec2Out = { x: 0, y: 0 };
