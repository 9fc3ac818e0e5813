/**
 * The progress bar of `pathwise render`, drawn on stderr when it is a
 * terminal: how far the render is towards whichever stop comes first (the
 * sample count, the time budget, the noise target), and an ETA.
 *
 *   [##########..........]  52%  133/256 spp  0:12  ETA 0:11  noise 0.031 → 0.020
 */

export interface ProgressState {
  /** Samples per pixel done so far (fractional within a round), counted from the range start. */
  spp: number;
  /** Samples per pixel already there when this process started (a resumed checkpoint). */
  sppFrom: number;
  /** The most samples this render will take (the range length). */
  sppTarget: number;
  /** Seconds since the render started (this process). */
  elapsed: number;
  /** Seconds left of a --time budget, if any. */
  timeLeft?: number;
  /** Latest noise estimate and the --noise target, if any. */
  noise?: number;
  noiseTarget?: number;
  /** Samples per pixel at which `noise` was estimated. */
  noiseSpp?: number;
  /** The render has stopped (by whichever criterion): 100%, nothing left. */
  done?: boolean;
}

/** "0:07", "12:34", "1:02:03" */
export function formatDuration(seconds: number): string {
  if (!Number.isFinite(seconds) || seconds < 0) return '--:--';
  const s = Math.round(seconds);
  const h = Math.floor(s / 3600);
  const m = Math.floor((s % 3600) / 60);
  const ss = String(s % 60).padStart(2, '0');
  return h > 0 ? `${h}:${String(m).padStart(2, '0')}:${ss}` : `${m}:${ss}`;
}

/**
 * Fraction done and seconds left. Each stop criterion gives its own
 * estimate; the render ends at the first, so the largest fraction wins.
 * The noise criterion predicts the samples it needs from noise ∝ 1/√spp.
 */
export function estimateProgress(p: ProgressState): { fraction: number; eta: number } {
  if (p.done) return { fraction: 1, eta: 0 };
  // This process's rate: samples from a resumed checkpoint took no time here.
  const rate = p.elapsed > 0 && p.spp > p.sppFrom ? (p.spp - p.sppFrom) / p.elapsed : 0;
  let fraction = p.sppTarget > 0 ? p.spp / p.sppTarget : 0;
  let eta = rate > 0 ? (p.sppTarget - p.spp) / rate : Infinity;
  if (p.timeLeft !== undefined) {
    const f = p.elapsed / (p.elapsed + Math.max(0, p.timeLeft));
    if (f > fraction) fraction = f;
    eta = Math.min(eta, Math.max(0, p.timeLeft));
  }
  if (
    p.noiseTarget !== undefined &&
    p.noise !== undefined &&
    Number.isFinite(p.noise) &&
    p.noiseSpp !== undefined &&
    p.noiseSpp > 0
  ) {
    const needed = p.noiseSpp * (p.noise / p.noiseTarget) ** 2;
    const f = needed > 0 ? Math.min(1, p.spp / needed) : 1;
    if (f > fraction) fraction = f;
    if (rate > 0) eta = Math.min(eta, Math.max(0, needed - p.spp) / rate);
  }
  return { fraction: Math.min(1, Math.max(0, fraction)), eta };
}

export function formatProgress(p: ProgressState, columns = 80): string {
  const { fraction, eta } = estimateProgress(p);
  const percent = `${Math.floor(fraction * 100)}%`.padStart(4);
  const spp = `${Math.floor(p.spp)}/${p.sppTarget} spp`;
  let tail = `  ${percent}  ${spp}  ${formatDuration(p.elapsed)}  ETA ${formatDuration(eta)}`;
  if (p.noiseTarget !== undefined) {
    const now = p.noise !== undefined && Number.isFinite(p.noise) ? p.noise.toPrecision(2) : '?';
    tail += `  noise ${now} → ${p.noiseTarget}`;
  }
  const barWidth = Math.max(10, Math.min(30, columns - tail.length - 3));
  const filled = Math.round(fraction * barWidth);
  const line = `[${'#'.repeat(filled)}${'.'.repeat(barWidth - filled)}]${tail}`;
  return line.length > columns - 1 ? line.slice(0, columns - 1) : line;
}

/** Redraws one line of stderr in place (only when stderr is a terminal). */
export class ProgressBar {
  private readonly stream: NodeJS.WritableStream;
  private readonly columns: number;
  private drawn = false;

  constructor(stream: NodeJS.WritableStream, columns: number) {
    this.stream = stream;
    this.columns = columns;
  }

  update(p: ProgressState): void {
    this.stream.write(`\r${formatProgress(p, this.columns)}\x1b[K`);
    this.drawn = true;
  }

  /**
   * Draws the final state (however short the render, the bar shows once)
   * and ends the line so later messages start on their own.
   */
  finish(final?: ProgressState): void {
    if (final) this.update({ ...final, done: true });
    if (this.drawn) this.stream.write('\n');
    this.drawn = false;
  }
}
