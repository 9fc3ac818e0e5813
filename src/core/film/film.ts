/**
 * The accumulator: per-pixel running sums of radiance, in Float32 so the
 * display can upload them as an RGBA32F texture without conversion.
 *
 * Layout of the backing buffer (which may be a SharedArrayBuffer, so that
 * every worker writes its own rows in place):
 *   sums  [width·rows·4]  R, G, B sums and the count of accepted samples (A)
 *   extra [width·rows·4]  Kahan compensation for R, G, B, and the running sum
 *                         of squared luminance (for the noise estimate)
 *
 * Why Kahan: adding 0.1 to a Float32 sum 65,536 times drifts by ~1e-3
 * relative because each add rounds to 24 bits. Compensated summation
 * (Kahan 1965; Higham, "Accuracy and Stability of Numerical Algorithms"
 * §4.3) carries the lost low bits in a second Float32, which keeps the
 * error at a few ulps whatever the sample count. The arithmetic runs in
 * doubles; only the stored values are rounded to Float32.
 *
 * A film may cover only a window of rows [y0, y0+rows) of the image: the
 * non-shared fallback ships single stripes between threads.
 */
/** The largest finite Float32. */
const FLOAT32_MAX = 3.4028234663852886e38;

export class Film {
  readonly width: number;
  readonly rows: number;
  readonly y0: number;
  readonly buffer: ArrayBuffer | SharedArrayBuffer;
  /** RGBA: linear radiance sums and the accepted-sample count. */
  readonly sums: Float32Array;
  /** RGB Kahan compensation, A: sum of squared luminance. */
  readonly extra: Float32Array;

  static byteLength(width: number, rows: number): number {
    return width * rows * 8 * Float32Array.BYTES_PER_ELEMENT;
  }

  constructor(
    width: number,
    rows: number,
    buffer?: ArrayBuffer | SharedArrayBuffer,
    y0 = 0,
    byteOffset = 0,
  ) {
    this.width = width;
    this.rows = rows;
    this.y0 = y0;
    const n = width * rows * 4;
    this.buffer = buffer ?? new ArrayBuffer(Film.byteLength(width, rows));
    if (this.buffer.byteLength - byteOffset < Film.byteLength(width, rows)) {
      throw new RangeError(
        `film buffer of ${this.buffer.byteLength} bytes is too small for ${width}×${rows}`,
      );
    }
    this.sums = new Float32Array(this.buffer, byteOffset, n);
    this.extra = new Float32Array(this.buffer, byteOffset + n * 4, n);
  }

  /**
   * Adds one sample of radiance to pixel (x, y) (image coordinates). Returns
   * false, adding nothing, when the sample is not finite (one NaN would
   * otherwise poison the pixel for the rest of the run) or when adding it
   * would overflow a Float32 sum to Infinity. The loader's radiance bound
   * (1e12) keeps sums far from overflow; this check makes sure that no
   * non-finite value ever reaches the film, whatever the sample count. The
   * caller counts the rejected samples.
   */
  addSample(x: number, y: number, r: number, g: number, b: number): boolean {
    if (!(Number.isFinite(r) && Number.isFinite(g) && Number.isFinite(b))) return false;
    const i = ((y - this.y0) * this.width + x) * 4;
    const sums = this.sums;
    const extra = this.extra;
    const yr = r - extra[i];
    const yg = g - extra[i + 1];
    const yb = b - extra[i + 2];
    const sr = sums[i];
    const sg = sums[i + 1];
    const sb = sums[i + 2];
    const tr = Math.fround(sr + yr);
    const tg = Math.fround(sg + yg);
    const tb = Math.fround(sb + yb);
    const lum = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    const squares = Math.fround(extra[i + 3] + lum * lum);
    // |t| <= FLOAT32_MAX is false for ±Infinity (and NaN): nothing is written then.
    if (!(
      Math.abs(tr) <= FLOAT32_MAX &&
      Math.abs(tg) <= FLOAT32_MAX &&
      Math.abs(tb) <= FLOAT32_MAX &&
      squares <= FLOAT32_MAX
    )) {
      return false;
    }
    extra[i] = tr - sr - yr;
    sums[i] = tr;
    extra[i + 1] = tg - sg - yg;
    sums[i + 1] = tg;
    extra[i + 2] = tb - sb - yb;
    sums[i + 2] = tb;
    sums[i + 3] += 1;
    extra[i + 3] = squares;
    return true;
  }

  /** Clears every sum (e.g. after a scene or camera change). */
  clear(): void {
    this.sums.fill(0);
    this.extra.fill(0);
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
}
