/**
 * How far the demo's image is from the truth, estimated and measured, on
 * a grid of cells that the film's pixels and a reference's pixels both
 * tile exactly.
 *
 * The references (tests/references, Mitsuba 3 at 65,536 spp) are 128×128
 * renders of a canonical scene's own camera. The camera frames the
 * vertical field of view whatever the aspect ratio (pathwise-scene/1), so
 * the reference covers the film's full height and a centred span of its
 * width (or more than the width, on a portrait film). A cell is g × g
 * reference pixels and k × k film pixels; since every pixel is the box
 * filter of radiance over its square (a pixel's mean), the mean of a cell's
 * film pixels estimates exactly what the mean of its reference pixels is,
 * with no resampling bias. That needs whole numbers: G = 128 / g rows of
 * cells dividing the film's height, and the centred square starting on a
 * film pixel (width and height of one parity), which the demo's size step
 * guarantees (PathTracerOptions.sizeStep).
 *
 * Per cell c, on luminance L (the film's weights, Rec. 709):
 *
 *   true       e_c = (L̂_c − R_c)² / (R_c² + ε)
 *   estimated  v_c = Var̂(L̂_c) / (L̂_c² + ε),  Var̂(L̂_c) = Σ_p s_p² / n_p / (k²)²
 *
 * with s_p² the sample variance of pixel p's n_p samples (the film's exact
 * sums keep ΣL²) and ε = 0.01, the usual relMSE guard against division by black
 * (as in pbrt-v4's imgtool). relMSE is the mean over cells; the estimate
 * needs no reference, so every scene has one. Each is a mean square: its
 * square root falls as 1/√t, which is what the demo plots.
 *
 * The variance estimate treats a pixel's samples as independent. The
 * default sampler (Owen-scrambled Sobol) stratifies the first dimensions,
 * so the true error can fall below the estimate; with independent samples
 * the two agree in expectation (tests/unit/app/error-grid.test.ts).
 */
import { exactValue } from '../core/index.ts';

export const REL_MSE_EPSILON = 0.01;
/** Cells per side at most: plenty for a mean, cheap to read a few times a second. */
export const MAX_GRID_ROWS = 64;
/** Fewer rows than this and the grid says little about the picture: no figures. */
export const MIN_GRID_ROWS = 16;

const LUM_R = 0.2126;
const LUM_G = 0.7152;
const LUM_B = 0.0722;

/** A reference image reduced to what the comparison needs. */
export interface ReferenceLuminance {
  width: number;
  height: number;
  /** Luminance per pixel, row 0 at the top. */
  lum: Float64Array;
}

export function referenceLuminance(width: number, height: number, rgb: ArrayLike<number>) {
  const lum = new Float64Array(width * height);
  for (let p = 0; p < lum.length; p++) {
    lum[p] = LUM_R * rgb[p * 3] + LUM_G * rgb[p * 3 + 1] + LUM_B * rgb[p * 3 + 2];
  }
  return { width, height, lum } satisfies ReferenceLuminance;
}

export interface GridLayout {
  /** Rows of cells. */
  rows: number;
  /** Columns of cells (inside the film). */
  columns: number;
  /** Film pixels per cell side. */
  k: number;
  /** Reference pixels per cell side. */
  g: number;
  /** Film x of the first used column's left edge. */
  filmX0: number;
  /** Reference column (in cells) of the first used column. */
  refColumn0: number;
}

function gcd(a: number, b: number): number {
  while (b) [a, b] = [b, a % b];
  return a;
}

/**
 * The cell grid for a film of width × height against a reference of
 * refWidth × refHeight framing the same vertical field of view, or null
 * when the sizes do not tile (the film's height shares too small a factor
 * with the reference's, or the centred reference does not start on a film
 * pixel).
 */
export function gridLayout(
  width: number,
  height: number,
  refWidth: number,
  refHeight: number,
): GridLayout | null {
  const common = gcd(height, refHeight);
  // The finest grid that tiles: most rows, at most MAX_GRID_ROWS.
  for (let rows = Math.min(MAX_GRID_ROWS, common); rows >= MIN_GRID_ROWS; rows--) {
    if (common % rows !== 0) continue;
    const k = height / rows;
    const g = refHeight / rows;
    if (refWidth % g !== 0) continue;
    const refColumns = refWidth / g;
    // Film x of the reference's left edge: centred, k film pixels per cell.
    const twice = width - refColumns * k;
    if (twice % 2 !== 0) continue;
    const left = twice / 2;
    const first = left >= 0 ? 0 : Math.ceil(-left / k);
    const last = Math.min(refColumns, Math.floor((width - left) / k));
    if (last - first < 1) continue;
    return { rows, columns: last - first, k, g, filmX0: left + first * k, refColumn0: first };
  }
  return null;
}

/**
 * The render-height step that lets a film tile the grid of a reference of
 * refWidth × refHeight (with an even width): the most grid rows that divide
 * the reference's height and columns, e.g. 64 for 128 × 128, 45 for 160 × 90.
 */
export function gridStep(refWidth: number, refHeight: number): number {
  for (let rows = Math.min(MAX_GRID_ROWS, refHeight); rows >= MIN_GRID_ROWS; rows--) {
    const g = refHeight / rows;
    if (Number.isInteger(g) && refWidth % g === 0) return rows;
  }
  return 1;
}

export interface ErrorFigures {
  /** Mean over cells of the true squared relative error (NaN without a reference or samples). */
  relMse: number;
  /** The same, estimated from the film's own per-pixel variance (NaN below 2 samples). */
  estimatedRelMse: number;
  /** Cells that entered each mean. */
  cells: number;
}

/**
 * relMSE against `reference` (null: only the estimate) on the grid,
 * visiting every other cell in a checkerboard, for a film `width` pixels
 * wide with `sums` (RGB, samples) and `squares`: Σ luminance² per pixel, at
 * index 4p + 3 — the film's exact sums ({ hi, lo }, film/exact-sum.ts), or
 * a plain array. Reads the arrays once; allocates nothing.
 */
export function errorFigures(
  width: number,
  sums: Float32Array,
  squares: Float32Array | { hi: Float64Array; lo: Float64Array },
  layout: GridLayout,
  reference: ReferenceLuminance | null,
): ErrorFigures {
  const { rows, columns, k, g, filmX0, refColumn0 } = layout;
  const exact = squares instanceof Float32Array ? null : squares;
  const plain = squares instanceof Float32Array ? squares : null;
  const perCell = k * k;
  let trueSum = 0;
  let estSum = 0;
  let cells = 0;
  let estCells = 0;
  for (let cy = 0; cy < rows; cy++) {
    for (let cx = (cy & 1) as number; cx < columns; cx += 2) {
      let lumMeans = 0;
      let se2 = 0;
      let minCount = Infinity;
      const x0 = filmX0 + cx * k;
      for (let y = cy * k; y < (cy + 1) * k; y++) {
        for (let x = x0; x < x0 + k; x++) {
          const i = (y * width + x) * 4;
          const n = sums[i + 3];
          if (n < minCount) minCount = n;
          if (n < 1) continue;
          const sumL = LUM_R * sums[i] + LUM_G * sums[i + 1] + LUM_B * sums[i + 2];
          const mean = sumL / n;
          lumMeans += mean;
          if (n >= 2) {
            const sq = exact ? exactValue(exact.hi, exact.lo, i + 3) : plain![i + 3];
            const ss = sq - n * mean * mean;
            if (ss > 0) se2 += ss / (n - 1) / n;
          }
        }
      }
      if (minCount < 1) continue;
      const cellLum = lumMeans / perCell;
      if (minCount >= 2) {
        estSum += se2 / (perCell * perCell) / (cellLum * cellLum + REL_MSE_EPSILON);
        estCells++;
      }
      if (reference) {
        let refSum = 0;
        const rx0 = (refColumn0 + cx) * g;
        for (let ry = cy * g; ry < (cy + 1) * g; ry++) {
          for (let rx = rx0; rx < rx0 + g; rx++) refSum += reference.lum[ry * reference.width + rx];
        }
        const r = refSum / (g * g);
        const d = cellLum - r;
        trueSum += (d * d) / (r * r + REL_MSE_EPSILON);
      }
      cells++;
    }
  }
  return {
    relMse: reference && cells > 0 ? trueSum / cells : NaN,
    estimatedRelMse: estCells > 0 ? estSum / estCells : NaN,
    cells,
  };
}
