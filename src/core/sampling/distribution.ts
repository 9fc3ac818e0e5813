/**
 * Piecewise-constant distributions (pbr-book 4e §A.5.1 "Piecewise-Constant 1D
 * Distributions", §A.5.6 "Piecewise-Constant 2D Distributions"), with sample, pdf and
 * inverse. Cells are found by binary search in a CDF rather than an alias table: the
 * CDF maps u to cells monotonically, so stratified and low-discrepancy numbers stay
 * stratified across cells, which an alias table would scramble.
 *
 * Probabilities are always read back from the stored CDF (never from the weights), so
 * `sample` and `prob` agree exactly even where rounding of the CDF merged a faint cell
 * into its neighbour: such a cell has probability 0 for both, and MIS with another
 * strategy covers it without bias.
 */
import type { Vec2Out } from './warps.ts';

export class Distribution1D {
  readonly count: number;
  /** count + 1 entries from 0 to 1. */
  readonly cdf: Float64Array;
  /** Sum of the weights (0 when every weight is 0; then the CDF is uniform). */
  readonly total: number;

  constructor(weights: ArrayLike<number>) {
    const n = weights.length;
    this.count = n;
    this.cdf = new Float64Array(n + 1);
    let total = 0;
    for (let i = 0; i < n; i++) {
      total += weights[i];
      this.cdf[i + 1] = total;
    }
    this.total = total;
    for (let i = 1; i <= n; i++) this.cdf[i] = total > 0 ? this.cdf[i] / total : i / n;
    this.cdf[n] = 1;
  }

  /** The cell i with cdf[i] ≤ u < cdf[i + 1], for u in [0, 1); never a cell of width 0. */
  find(u: number): number {
    const cdf = this.cdf;
    let lo = 0;
    let hi = this.count - 1;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (cdf[mid + 1] <= u) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  }

  /** Probability of cell i. */
  prob(i: number): number {
    return this.cdf[i + 1] - this.cdf[i];
  }

  /** Where u falls inside cell i, in [0, 1): the number reused for a sample inside it. */
  remap(u: number, i: number): number {
    const lo = this.cdf[i];
    const f = (u - lo) / (this.cdf[i + 1] - lo);
    return f < 1 ? f : ONE_MINUS_EPSILON;
  }

  /** The u that `find` and `remap` take to cell i at offset f. */
  invert(i: number, f: number): number {
    return this.cdf[i] + f * (this.cdf[i + 1] - this.cdf[i]);
  }
}

const ONE_MINUS_EPSILON = 1 - 2 ** -53;

/**
 * A distribution over the cells of a width × height grid, as a marginal over rows and a
 * conditional over the columns of each row. The conditional CDFs are Float32 (4 bytes
 * per cell: a 16384 × 8192 environment map needs 512 MiB for them, not 1 GiB), which
 * is safe because probabilities are read back from the same stored values.
 */
export class Distribution2D {
  readonly width: number;
  readonly height: number;
  readonly marginal: Distribution1D;
  /** height rows of width + 1 entries. */
  readonly conditional: Float32Array;

  /** `fillRow(row, out)` writes the non-negative weights of one row into `out`. */
  constructor(width: number, height: number, fillRow: (row: number, out: Float64Array) => void) {
    this.width = width;
    this.height = height;
    const stride = width + 1;
    this.conditional = new Float32Array(height * stride);
    const rowSums = new Float64Array(height);
    const row = new Float64Array(width);
    for (let y = 0; y < height; y++) {
      row.fill(0);
      fillRow(y, row);
      let sum = 0;
      for (let x = 0; x < width; x++) sum += row[x];
      rowSums[y] = sum;
      const o = y * stride;
      let acc = 0;
      for (let x = 0; x < width; x++) {
        acc += row[x];
        this.conditional[o + x + 1] = sum > 0 ? acc / sum : (x + 1) / width;
      }
      this.conditional[o + width] = 1;
    }
    this.marginal = new Distribution1D(rowSums);
  }

  /** Total weight of the grid. */
  get total(): number {
    return this.marginal.total;
  }

  /**
   * Picks a cell with u1 (row) and u0 (column) and writes the continuous point in
   * [0, width) × [0, height) to `out`; returns the cell's probability.
   */
  sample(u0: number, u1: number, out: Vec2Out): number {
    const m = this.marginal;
    const y = m.find(u1);
    const fy = m.remap(u1, y);
    const x = this.findInRow(y, u0);
    const o = y * (this.width + 1);
    const lo = this.conditional[o + x];
    const width = this.conditional[o + x + 1] - lo;
    let fx = (u0 - lo) / width;
    if (!(fx < 1)) fx = ONE_MINUS_EPSILON;
    out.x = x + fx;
    out.y = y + fy;
    return m.prob(y) * width;
  }

  /** Probability of cell (x, y). */
  prob(x: number, y: number): number {
    const o = y * (this.width + 1);
    return this.marginal.prob(y) * (this.conditional[o + x + 1] - this.conditional[o + x]);
  }

  /** The (u0, u1) that `sample` takes to the continuous point (x, y). */
  invert(x: number, y: number, out: Vec2Out): void {
    const cx = Math.min(this.width - 1, Math.floor(x));
    const cy = Math.min(this.height - 1, Math.floor(y));
    const o = cy * (this.width + 1);
    const lo = this.conditional[o + cx];
    out.x = lo + (x - cx) * (this.conditional[o + cx + 1] - lo);
    out.y = this.marginal.invert(cy, y - cy);
  }

  private findInRow(y: number, u: number): number {
    const c = this.conditional;
    const o = y * (this.width + 1);
    let lo = 0;
    let hi = this.width - 1;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (c[o + mid + 1] <= u) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  }
}
