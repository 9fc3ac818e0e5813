/**
 * The accumulator: per-pixel exact sums of radiance, and Float32 copies of
 * them that the display uploads as an RGBA32F texture without conversion.
 *
 * Layout of the backing buffer (which may be a SharedArrayBuffer, so that
 * every worker writes its own rows in place), n = width·rows:
 *   sums [4n] Float32  R, G, B sums rounded from the exact sums, and A: the
 *                      count of accepted samples — the display's contract
 *   hi   [4n] Float64  high limbs of the exact sums of R, G, B and of the
 *                      squared luminance (for the noise estimate)
 *   lo   [4n] Float64  their low limbs
 * 80 bytes per pixel. A film made with `aux` adds the denoising features
 * (integrator/aux.ts), exact sums over the same accepted samples:
 *   auxHi [6n] Float64  high limbs of albedo R, G, B and normal X, Y, Z
 *   auxLo [6n] Float64  their low limbs
 * 96 bytes more per pixel.
 *
 * The exact sums (see exact-sum.ts) make a pixel's value independent of
 * the order and grouping of its samples: threads, stripe layouts, sample
 * ranges rendered on other machines, checkpoints and resumes all give the
 * same bits. `sums` is always the one rounding of the exact sum, so it is
 * split-independent too.
 *
 * A film may cover only a window of rows [y0, y0+rows) of the image: the
 * non-shared fallback ships single stripes between threads.
 */
import { SAMPLE_LIMIT, addExact, addFixed, exactValue } from './exact-sum.ts';

/** Exact-sum channels of the aux planes per pixel: albedo RGB, normal XYZ. */
export const AUX_CHANNELS = 6;

/** Rec. 709 luminance weights, as in the noise estimate. */
const LUM_R = 0.2126;
const LUM_G = 0.7152;
const LUM_B = 0.0722;
/**
 * Squared luminance above this is added as this: it feeds only the noise
 * estimate, and keeps the exact sum in range (luminance ≤ 2^20 ≈ 1e6 is
 * kept exactly).
 */
export const LUM2_LIMIT = 2 ** 40;

/**
 * The radiance of one sample as fields of a record (PathTracer is one): a
 * call V8 does not inline boxes each double argument on the heap, and the
 * tracer's row loop does not inline the film's add.
 */
export interface Radiance {
  lr: number;
  lg: number;
  lb: number;
}

/** One sample's albedo and shading normal (integrator/aux.ts writes them). */
export interface AuxValues {
  ar: number;
  ag: number;
  ab: number;
  nx: number;
  ny: number;
  nz: number;
}

export class Film {
  readonly width: number;
  readonly rows: number;
  readonly y0: number;
  readonly buffer: ArrayBuffer | SharedArrayBuffer;
  /** RGBA: linear radiance sums (rounded from the exact sums) and the accepted-sample count. */
  readonly sums: Float32Array;
  /** High limbs of the exact sums of R, G, B and squared luminance. */
  readonly hi: Float64Array;
  /** Low limbs of the same. */
  readonly lo: Float64Array;
  /** High limbs of the exact sums of albedo R, G, B and normal X, Y, Z; null without aux. */
  readonly auxHi: Float64Array | null;
  /** Low limbs of the same. */
  readonly auxLo: Float64Array | null;
  /** addSample's record for addRadiance. */
  private readonly sample: Radiance = { lr: 0, lg: 0, lb: 0 };

  static byteLength(width: number, rows: number, aux = false): number {
    return width * rows * (aux ? 80 + 16 * AUX_CHANNELS : 80);
  }

  constructor(
    width: number,
    rows: number,
    buffer?: ArrayBuffer | SharedArrayBuffer,
    y0 = 0,
    byteOffset = 0,
    aux = false,
  ) {
    this.width = width;
    this.rows = rows;
    this.y0 = y0;
    const n = width * rows * 4;
    this.buffer = buffer ?? new ArrayBuffer(Film.byteLength(width, rows, aux));
    if (this.buffer.byteLength - byteOffset < Film.byteLength(width, rows, aux)) {
      throw new RangeError(
        `film buffer of ${this.buffer.byteLength} bytes is too small for ${width}×${rows}`,
      );
    }
    if (byteOffset % 8 !== 0)
      throw new RangeError(`film byteOffset ${byteOffset} is not 8-aligned`);
    this.sums = new Float32Array(this.buffer, byteOffset, n);
    this.hi = new Float64Array(this.buffer, byteOffset + n * 4, n);
    this.lo = new Float64Array(this.buffer, byteOffset + n * 12, n);
    const na = width * rows * AUX_CHANNELS;
    this.auxHi = aux ? new Float64Array(this.buffer, byteOffset + n * 20, na) : null;
    this.auxLo = aux ? new Float64Array(this.buffer, byteOffset + n * 20 + na * 8, na) : null;
  }

  /**
   * Adds one sample of radiance to pixel (x, y) (image coordinates). Returns
   * false, adding nothing, when a component is not finite or beyond
   * ±SAMPLE_LIMIT: one NaN would otherwise poison the pixel for the rest
   * of the run.
   */
  addSample(x: number, y: number, r: number, g: number, b: number): boolean {
    const s = this.sample;
    s.lr = r;
    s.lg = g;
    s.lb = b;
    return this.addRadiance(x, y, s);
  }

  /** addSample with the radiance read from `s` (see Radiance). */
  addRadiance(x: number, y: number, s: Radiance): boolean {
    const r = s.lr;
    const g = s.lg;
    const b = s.lb;
    if (!(
      Math.abs(r) <= SAMPLE_LIMIT &&
      Math.abs(g) <= SAMPLE_LIMIT &&
      Math.abs(b) <= SAMPLE_LIMIT
    ))
      return false;
    const i = ((y - this.y0) * this.width + x) * 4;
    const sums = this.sums;
    const hi = this.hi;
    const lo = this.lo;
    sums[i] = addFixed(hi, lo, i, r);
    sums[i + 1] = addFixed(hi, lo, i + 1, g);
    sums[i + 2] = addFixed(hi, lo, i + 2, b);
    sums[i + 3] += 1;
    const lum = LUM_R * r + LUM_G * g + LUM_B * b;
    // Math.min rather than `lum2 < LUM2_LIMIT ? lum2 : LUM2_LIMIT`: V8 gave
    // that select a tagged representation, one heap number per sample.
    addFixed(hi, lo, i + 3, Math.min(lum * lum, LUM2_LIMIT));
    return true;
  }

  /**
   * addRadiance with the sample's albedo and normal (a film made with aux): the
   * sample is accepted, into all planes, only when radiance and aux are all finite
   * and in range, so the aux means are over exactly the radiance's samples.
   */
  addSampleAux(x: number, y: number, s: Radiance, a: AuxValues): boolean {
    if (!(
      Math.abs(a.ar) <= SAMPLE_LIMIT &&
      Math.abs(a.ag) <= SAMPLE_LIMIT &&
      Math.abs(a.ab) <= SAMPLE_LIMIT &&
      Math.abs(a.nx) <= SAMPLE_LIMIT &&
      Math.abs(a.ny) <= SAMPLE_LIMIT &&
      Math.abs(a.nz) <= SAMPLE_LIMIT
    ))
      return false;
    if (!this.addRadiance(x, y, s)) return false;
    const i = ((y - this.y0) * this.width + x) * AUX_CHANNELS;
    const hi = this.auxHi!;
    const lo = this.auxLo!;
    addFixed(hi, lo, i, a.ar);
    addFixed(hi, lo, i + 1, a.ag);
    addFixed(hi, lo, i + 2, a.ab);
    addFixed(hi, lo, i + 3, a.nx);
    addFixed(hi, lo, i + 4, a.ny);
    addFixed(hi, lo, i + 5, a.nz);
    return true;
  }

  /**
   * Adds every sample of `other` (same width; its rows must lie inside this
   * film's) exactly: the result is the same bits as if this film had
   * received those samples itself.
   */
  add(other: Film): void {
    if (
      other.width !== this.width ||
      other.y0 < this.y0 ||
      other.y0 + other.rows > this.y0 + this.rows
    ) {
      throw new RangeError('film.add: the other film does not fit inside this one');
    }
    if ((this.auxHi === null) !== (other.auxHi === null)) {
      throw new RangeError('film.add: one film has albedo and normal planes and the other not');
    }
    const base = (other.y0 - this.y0) * this.width * 4;
    const sums = this.sums;
    const hi = this.hi;
    const lo = this.lo;
    const oh = other.hi;
    const ol = other.lo;
    const oc = other.sums;
    for (let j = 0, n = oh.length; j < n; j += 4) {
      const i = base + j;
      for (let c = 0; c < 4; c++) addExact(hi, lo, i + c, oh[j + c], ol[j + c]);
      sums[i] = exactValue(hi, lo, i);
      sums[i + 1] = exactValue(hi, lo, i + 1);
      sums[i + 2] = exactValue(hi, lo, i + 2);
      sums[i + 3] += oc[j + 3];
    }
    if (this.auxHi !== null) {
      const ah = this.auxHi;
      const al = this.auxLo!;
      const oah = other.auxHi!;
      const oal = other.auxLo!;
      const abase = (other.y0 - this.y0) * this.width * AUX_CHANNELS;
      for (let j = 0, n = oah.length; j < n; j++) addExact(ah, al, abase + j, oah[j], oal[j]);
    }
  }

  /** Recomputes the Float32 RGB sums from the exact sums (after hi and lo were filled directly). */
  resolve(): void {
    const sums = this.sums;
    const hi = this.hi;
    const lo = this.lo;
    for (let i = 0, n = sums.length; i < n; i += 4) {
      sums[i] = exactValue(hi, lo, i);
      sums[i + 1] = exactValue(hi, lo, i + 1);
      sums[i + 2] = exactValue(hi, lo, i + 2);
    }
  }

  /**
   * Copies every plane of the rows that this film and `from` share (same
   * width): how a one-row or one-stripe window travels between a worker
   * and the full film.
   */
  copyRowsFrom(from: Film): void {
    if (from.width !== this.width) throw new RangeError('film.copyRowsFrom: widths differ');
    const y0 = Math.max(this.y0, from.y0);
    const y1 = Math.min(this.y0 + this.rows, from.y0 + from.rows);
    if (y1 <= y0) return;
    const w4 = this.width * 4;
    const a = (y0 - from.y0) * w4;
    const b = (y1 - from.y0) * w4;
    const at = (y0 - this.y0) * w4;
    this.sums.set(from.sums.subarray(a, b), at);
    this.hi.set(from.hi.subarray(a, b), at);
    this.lo.set(from.lo.subarray(a, b), at);
    if (this.auxHi !== null && from.auxHi !== null) {
      const w6 = this.width * AUX_CHANNELS;
      const aa = (y0 - from.y0) * w6;
      const ab = (y1 - from.y0) * w6;
      const aat = (y0 - this.y0) * w6;
      this.auxHi.set(from.auxHi.subarray(aa, ab), aat);
      this.auxLo!.set(from.auxLo!.subarray(aa, ab), aat);
    }
  }

  /** Clears every sum (e.g. after a scene or camera change). */
  clear(): void {
    this.sums.fill(0);
    this.hi.fill(0);
    this.lo.fill(0);
    this.auxHi?.fill(0);
    this.auxLo?.fill(0);
  }

  /** Mean radiance image, RGB float32 row-major with row 0 at the top. */
  mean(): Float32Array {
    const out = new Float32Array(this.width * this.rows * 3);
    const sums = this.sums;
    for (let p = 0, n = this.width * this.rows; p < n; p++) {
      const count = sums[p * 4 + 3];
      const inv = count > 0 ? 1 / count : 0;
      out[p * 3] = sums[p * 4] * inv;
      out[p * 3 + 1] = sums[p * 4 + 1] * inv;
      out[p * 3 + 2] = sums[p * 4 + 2] * inv;
    }
    return out;
  }

  /**
   * Mean albedo (`channel` 0) or normal (`channel` 3) image, RGB float32 row-major
   * with row 0 at the top: each exact sum read once (exactValue) over the pixel's
   * accepted samples. Zero where a pixel has none. Throws on a film without aux.
   */
  auxMean(channel: 0 | 3): Float32Array {
    const hi = this.auxHi;
    const lo = this.auxLo;
    if (hi === null || lo === null) throw new RangeError('film has no albedo and normal planes');
    const out = new Float32Array(this.width * this.rows * 3);
    const sums = this.sums;
    for (let p = 0, n = this.width * this.rows; p < n; p++) {
      const count = sums[p * 4 + 3];
      const i = p * AUX_CHANNELS + channel;
      for (let c = 0; c < 3; c++)
        out[p * 3 + c] = count > 0 ? exactValue(hi, lo, i + c) / count : 0;
    }
    return out;
  }
}
