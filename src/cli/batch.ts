/**
 * The round loop of `pathwise render`: which samples to add next, when to
 * stop (sample count, --time, --noise), when to write a checkpoint.
 *
 * A pass is one sample of every pixel; a round is a run of whole passes
 * [n, s1) handed to the worker pool. Because the film's sums are exact,
 * how the samples are cut into rounds never changes a bit — only where the
 * render may stop depends on it:
 *
 * - plain renders take every sample in one round (no overhead);
 * - --noise REL estimates the noise only at fixed sample counts of the
 *   range [A, B): A + m for m = 2, 3, …, with steps of max(1, ⌊m/16⌋)
 *   (every 64 samples at m = 1024). Rounds never cross these points, so
 *   the render stops at the same sample count whatever the thread count,
 *   timing, checkpoints or resumes — and the image is reproducible;
 * - --time SECONDS starts a round only if, at the measured seconds per
 *   pass (the slower of the last two rounds, plus 10%), it ends inside the
 *   budget (whole-process wall time, counted from process start) with
 *   time left to write the output; rounds take half the remaining passes,
 *   so the pass rate is re-measured as the deadline nears. The first pass
 *   always runs;
 * - --checkpoint ends rounds near each checkpoint time, then writes;
 * - an adaptive render whose film starts at sample 0 ends a round at the
 *   pilot's end, where the sample map is built from the film (adaptive.ts).
 */
import { estimateNoise } from '../core/film/noise.ts';
import type { RenderPool } from './render.ts';
import { processSeconds } from './host.ts';

export interface BatchPlan {
  /** Range start A (the noise schedule counts from it). */
  start: number;
  /** First sample to render: A, or where a checkpoint ended. */
  from: number;
  /** Range end B: the most samples to render. */
  end: number;
  /** --time budget in seconds of whole-process wall time. */
  time?: number;
  /** --noise target. */
  noise?: number;
  /** Seconds between checkpoints (with a checkpoint hook). */
  checkpointEvery?: number;
  /** Seconds set aside at the end of a --time budget to write the output. */
  reserve: number;
  /**
   * An adaptive render whose film holds the pilot (core/film/adaptive.ts): rounds end at
   * this sample count, where the `pilot` hook builds the sample map from the film.
   */
  pilotAt?: number;
}

export interface BatchHooks {
  /** Writes the film as holding samples [start, n). */
  checkpoint?: (n: number) => Promise<void>;
  /** The film holds exactly the pilot passes [0, plan.pilotAt): build the sample map. */
  pilot?: () => void;
  /** Called every 200 ms while rendering. */
  progress?: (state: BatchProgress) => void;
}

export interface BatchProgress {
  /** Sample index reached (fractional within a round: stripes done). */
  at: number;
  /** Seconds since runBatch started. */
  elapsed: number;
  /** Seconds left of the --time budget. */
  timeLeft?: number;
  /** Latest noise estimate (NaN before the first), and the sample index it was taken at. */
  noise: number;
  noiseAt: number;
}

export type StopReason = 'spp' | 'time' | 'noise';

export interface BatchResult {
  /** Samples [start, end) are in the film. */
  end: number;
  stop: StopReason;
  /** Seconds per pass in the last round (NaN if none ran). */
  passSeconds: number;
  checkpoints: number;
}

/** Seconds since the process started (the clock of --time). */
export { processSeconds };

/** Is `n` one of the sample counts at which --noise is checked (range starting at `start`)? */
export function isNoiseCheck(start: number, n: number): boolean {
  return nextNoiseCheck(start, n - 1) === n;
}

/** The first noise check point after sample count `n`. */
export function nextNoiseCheck(start: number, n: number): number {
  let m = 2;
  while (start + m <= n) m += Math.max(1, Math.floor(m / 16));
  return start + m;
}

export async function runBatch(
  pool: RenderPool,
  plan: BatchPlan,
  hooks: BatchHooks = {},
): Promise<BatchResult> {
  const t0 = processSeconds();
  const every = hooks.checkpoint ? plan.checkpointEvery : undefined;
  let n = plan.from;
  let passSeconds = NaN;
  /** The slower of the last two rounds' seconds per pass: what --time plans with. */
  let planSeconds = NaN;
  let lastCheckpoint = t0;
  let checkpoints = 0;
  let noise = NaN;
  let noiseAt = NaN;
  let round: [number, number] | undefined;

  const ticker = hooks.progress
    ? setInterval(() => {
        const at = round
          ? round[0] + ((round[1] - round[0]) * pool.stripesDone()) / pool.stripes
          : n;
        hooks.progress!({
          at,
          elapsed: processSeconds() - t0,
          timeLeft: plan.time !== undefined ? plan.time - processSeconds() : undefined,
          noise,
          noiseAt,
        });
      }, 200)
    : undefined;

  const checkNoise = (): boolean => {
    noise = estimateNoise(pool.film);
    noiseAt = n;
    return noise <= plan.noise!;
  };

  try {
    if (plan.pilotAt !== undefined && n === plan.pilotAt) hooks.pilot!();
    // A resumed render may sit on a check point already.
    if (plan.noise !== undefined && n > plan.start && isNoiseCheck(plan.start, n) && checkNoise()) {
      return { end: n, stop: 'noise', passSeconds, checkpoints };
    }
    for (;;) {
      if (n >= plan.end) return { end: n, stop: 'spp', passSeconds, checkpoints };
      let s1 = plan.end;
      if (plan.pilotAt !== undefined && n < plan.pilotAt) s1 = Math.min(s1, plan.pilotAt);
      if (plan.noise !== undefined) s1 = Math.min(s1, nextNoiseCheck(plan.start, n));
      if (plan.time !== undefined && Number.isFinite(passSeconds)) {
        const left = plan.time - processSeconds() - plan.reserve;
        // 10% margin on the slower of the last two rates: rounds vary, more so on a
        // shared machine.
        const fit = Math.floor(left / (planSeconds * 1.1));
        if (fit < 1) return { end: n, stop: 'time', passSeconds, checkpoints };
        s1 = Math.min(s1, n + Math.max(1, Math.ceil(fit / 2)));
      } else if (plan.time !== undefined) {
        s1 = Math.min(s1, n + 1);
      }
      if (every !== undefined) {
        const due = lastCheckpoint + every - processSeconds();
        const k = Number.isFinite(passSeconds) ? Math.max(1, Math.floor(due / passSeconds)) : 1;
        s1 = Math.min(s1, n + k);
      }
      round = [n, s1];
      const start = processSeconds();
      await pool.round(n, s1);
      const last = passSeconds;
      passSeconds = (processSeconds() - start) / (s1 - n);
      planSeconds = Number.isFinite(last) ? Math.max(last, passSeconds) : passSeconds;
      n = s1;
      round = undefined;
      if (n === plan.pilotAt) hooks.pilot!();
      if (plan.noise !== undefined && isNoiseCheck(plan.start, n) && checkNoise()) {
        return { end: n, stop: 'noise', passSeconds, checkpoints };
      }
      if (every !== undefined && processSeconds() - lastCheckpoint >= every && n < plan.end) {
        await hooks.checkpoint!(n);
        checkpoints++;
        lastCheckpoint = processSeconds();
      }
    }
  } finally {
    if (ticker) clearInterval(ticker);
  }
}
