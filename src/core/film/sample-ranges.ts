/**
 * Sets of sample indices as sorted, disjoint half-open ranges [a, b): what
 * a film holds (every pixel has exactly these samples), and what merging
 * films needs — overlaps are refused, gaps are reported.
 */

export type SampleRange = [number, number];

/** Samples in a set of disjoint ranges. */
export function rangeSamples(ranges: readonly SampleRange[]): number {
  let n = 0;
  for (const [a, b] of ranges) n += b - a;
  return n;
}

/**
 * The canonical form: sorted, with touching ranges joined. Returns null if
 * two ranges overlap (share a sample) — see `findOverlap` for which.
 */
export function normalizeRanges(ranges: readonly SampleRange[]): SampleRange[] | null {
  const sorted = ranges.map((r) => [r[0], r[1]] as SampleRange).sort((p, q) => p[0] - q[0]);
  const out: SampleRange[] = [];
  for (const r of sorted) {
    const last = out[out.length - 1];
    if (last && r[0] < last[1]) return null;
    if (last && r[0] === last[1]) last[1] = r[1];
    else out.push(r);
  }
  return out;
}

/** The first range [a, b) shared by the two sets, or null. */
export function findOverlap(
  x: readonly SampleRange[],
  y: readonly SampleRange[],
): SampleRange | null {
  for (const [a, b] of x) {
    for (const [c, d] of y) {
      const lo = Math.max(a, c);
      const hi = Math.min(b, d);
      if (lo < hi) return [lo, hi];
    }
  }
  return null;
}

/** The ranges of [0, total) that `ranges` (canonical) does not cover. */
export function missingRanges(ranges: readonly SampleRange[], total: number): SampleRange[] {
  const out: SampleRange[] = [];
  let at = 0;
  for (const [a, b] of ranges) {
    if (a > at) out.push([at, Math.min(a, total)]);
    at = Math.max(at, b);
    if (at >= total) break;
  }
  if (at < total) out.push([at, total]);
  return out.filter(([a, b]) => a < b);
}

/** "[0, 64) and [128, 256)" */
export function formatRanges(ranges: readonly SampleRange[]): string {
  const parts = ranges.map(([a, b]) => `[${a}, ${b})`);
  if (parts.length <= 1) return parts.join('');
  return `${parts.slice(0, -1).join(', ')} and ${parts[parts.length - 1]}`;
}
