/**
 * The quick first pass of a new scene and the automatic render scale
 * (auto-scale.ts), as a small state machine the controller drives once per
 * frame:
 *
 *   1. A scene loads: the controller renders the preview film. Its first
 *      pass puts a whole picture up at once; the speed of that pass sizes
 *      the full film (automatic scale), and the controller hands over.
 *   2. The full film refines on top of that picture; over its next passes
 *      the speed is measured again, warm, and the scale may rise once.
 *
 * It also keeps the timeline of the latest scene (load, first picture,
 * first full image) for the benchmarks.
 */
import {
  chooseRenderScale,
  PASS_BUDGET_S,
  RESCALE_MIN_GAIN,
  SpeedProbe,
  STEADY_PROBE_MS,
} from './auto-scale.ts';
import type { FilmJob } from './film-job.ts';
import type { Films } from './films.ts';

export interface Timeline {
  /** performance.now() of the latest scene load. */
  sceneLoaded: number;
  /** When a whole picture (the quick pass included) was first on screen (NaN: not yet). */
  firstPicture: number;
  /** When the full film's first whole pass was first drawn (NaN: not yet). */
  firstImage: number;
}

export class FirstPass {
  /** The quick pass is running in the preview film. */
  active = false;
  /** Samples per second the automatic scale was chosen from (NaN before one). */
  rate = NaN;
  readonly times: Timeline = { sceneLoaded: NaN, firstPicture: NaN, firstImage: NaN };
  private probe = new SpeedProbe();
  /** The warm measurement on the full film, while one is wanted. */
  private steady: SpeedProbe | null = null;
  private readonly films: Films;

  constructor(films: Films) {
    this.films = films;
  }

  /** A scene was loaded: a new timeline and a quick pass. */
  sceneLoaded(now: number): void {
    this.times.sceneLoaded = now;
    this.times.firstPicture = NaN;
    this.times.firstImage = NaN;
    this.start(now);
  }

  /** Runs a quick pass (and, with the automatic scale, measures again). */
  start(now: number): void {
    this.active = true;
    this.probe = new SpeedProbe(undefined, undefined, now);
    this.steady = null;
  }

  /** The film restarted or resumed: a warm measurement must not span that. */
  interrupted(): void {
    if (this.steady) this.steady = new SpeedProbe(1, STEADY_PROBE_MS);
  }

  /**
   * The automatic scale may still change: the quick pass runs, or the warm
   * measurement waits for the full film's passes (`fullDone`: the full film
   * reached its target, so none will come until the target rises).
   */
  measuring(fullDone: boolean): boolean {
    return this.active || (this.steady !== null && !fullDone);
  }

  /** The user set the scale: nothing left to measure. */
  manual(): void {
    this.steady = null;
  }

  /**
   * Feeds one frame (before drawing) with the active film. Returns true
   * when the controller must restart: the quick pass is over and the full
   * film takes over (unless the user is moving the camera), or the warm
   * measurement raised the scale.
   */
  advance(now: number, job: FilmJob, target: number, paused: boolean, interacting: boolean) {
    const films = this.films;
    if (this.active) {
      if (!films.previewing || job !== films.preview) return false;
      if (films.autoScale) {
        const finished = job.passesDone() >= target;
        const pixels = job.width * job.height;
        const rate = this.probe.update(now, job.progress(), job.passesDone(), pixels, finished);
        if (rate === null) return false;
        this.rate = rate;
        films.renderScale = this.scaleFor(rate);
        this.steady = new SpeedProbe(1, STEADY_PROBE_MS);
      } else if (job.passesDone() < 1) {
        return false;
      }
      this.active = false;
      // The whole preview pass becomes the backdrop the full film starts on.
      if (Number.isNaN(this.times.firstPicture)) this.times.firstPicture = now;
      return !interacting;
    }
    const steady = this.steady;
    if (!steady || paused || films.previewing || job !== films.full) return false;
    const rate = steady.update(now, job.progress(), job.passesDone(), job.width * job.height);
    if (rate === null) return false;
    this.steady = null;
    if (!films.autoScale) return false;
    const scale = this.scaleFor(rate);
    if (scale * scale < films.renderScale * films.renderScale * RESCALE_MIN_GAIN) return false;
    this.rate = rate;
    films.renderScale = scale;
    return films.ensureFull(target);
  }

  /** Timeline bookkeeping after a frame drew `job`, whose image has `spp` samples. */
  drew(now: number, job: FilmJob, spp: number): void {
    if (Number.isNaN(this.times.firstPicture) && job.passesDone() >= 1) {
      this.times.firstPicture = now;
    }
    if (Number.isNaN(this.times.firstImage) && spp >= 1) this.times.firstImage = now;
  }

  /** The automatic scale for `samplesPerSecond`, under the films' pixel cap (the denoiser's). */
  scaleFor(samplesPerSecond: number): number {
    const films = this.films;
    const css = films.cssSize();
    const pixels = css.width * css.height;
    return chooseRenderScale(
      samplesPerSecond,
      pixels,
      css.pixelRatio,
      PASS_BUDGET_S,
      films.maxAutoPixels,
    );
  }
}
