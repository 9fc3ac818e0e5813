/**
 * What the controller measures while it renders: rays and frames per
 * second, the time a draw takes, the noise estimate, and the `progress` and
 * `converged` events, sent only when they say something new.
 */
import { estimateNoise, filmIsEmpty } from '../core/index.ts';
import type { FilmJob } from './film-job.ts';
import { RateMeter } from './rate-meter.ts';
import type { ProgressInfo } from './types.ts';

/** Noise is estimated at most this often (it reads the whole film). */
const NOISE_INTERVAL_MS = 500;

/** What the meter reads from the controller when it reports (listeners may change it). */
export interface MeterHost {
  emit(type: string, detail: unknown): void;
  /** The target spp now. */
  target(): number;
  /** Whether the preview film is active (its passes are not the image's samples). */
  previewing(): boolean;
  /** A whole pass is done and the film accepted none of its `rejected` samples. */
  emptyImage(rejected: number): void;
}

export class ProgressMeter {
  private readonly host: MeterHost;
  private convergedSent = false;
  private readonly rays = new RateMeter();
  private readonly frames = new RateMeter();
  /** How long the last draw took. */
  frameMs = 0;
  /** Segments traced since the controller was made. */
  segmentsTotal = 0;
  private noise = NaN;
  private noiseAt = 0;
  private changedSinceNoise = false;
  private lastProgressAt = 0;
  /** spp and target of the last progress event (-1: none since the last restart). */
  private lastProgressSpp = -1;
  private lastProgressTarget = -1;
  /** Whether this film's first pass was checked for an empty image. */
  private emptyChecked = false;

  constructor(host: MeterHost) {
    this.host = host;
  }

  /** A restart: a new configuration, whose speed is measured afresh. */
  restarted(): void {
    this.convergedSent = false;
    this.rays.reset();
    this.cleared();
  }

  /** The film was cleared: its noise and progress are owed again. */
  cleared(): void {
    this.convergedSent = false;
    this.emptyChecked = false;
    this.noise = NaN;
    this.lastProgressSpp = -1;
  }

  /** A new target: `converged` is owed again once it is reached. */
  targetChanged(): void {
    this.convergedSent = false;
  }

  /** Segments the workers traced since the last frame. */
  traced(now: number, segments: number): void {
    this.segmentsTotal += segments;
    this.rays.add(now, segments);
  }

  /** A frame drew, taking `ms`. */
  drew(now: number, ms: number): void {
    this.frameMs = ms;
    this.frames.add(now, 1);
    this.changedSinceNoise = true;
  }

  /** The noise estimate, `progress` and `converged` after a frame. */
  update(now: number, job: FilmJob, spp: number): void {
    const host = this.host;
    // Once converged (or paused) nothing changes, so the film is not read
    // again for the noise estimate.
    if (this.changedSinceNoise && now - this.noiseAt > NOISE_INTERVAL_MS) {
      this.noiseAt = now;
      this.changedSinceNoise = false;
      // Every 4th pixel is plenty for a figure shown with two digits.
      this.noise = estimateNoise(job.film, 4);
    }
    // Progress only when it says something new, at most ~10 times a second;
    // the last step (the target reached) goes out at once.
    const progressChanged = this.owed(spp);
    if (progressChanged && (now - this.lastProgressAt > 100 || spp >= host.target())) {
      this.lastProgressAt = now;
      this.lastProgressSpp = spp;
      this.lastProgressTarget = host.target();
      host.emit('progress', this.info(spp, spp === 0 ? 0 : job.meanSamples()));
    }
    // Once per film, after its first whole pass: a film that accepted no
    // sample is no picture (empty-image.ts), so it is an error, not black.
    if (!this.emptyChecked && !host.previewing() && spp >= 1) {
      this.emptyChecked = true;
      const rejected = job.rejected();
      if (rejected > 0 && filmIsEmpty(job.film.sums)) {
        host.emptyImage(rejected);
        return;
      }
    }
    if (!this.convergedSent && !host.previewing() && spp >= host.target()) {
      this.convergedSent = true;
      host.emit('converged', this.info(spp, job.meanSamples()));
    }
  }

  /** Whether a `progress` event is still owed. */
  owed(spp: number): boolean {
    return spp !== this.lastProgressSpp || this.host.target() !== this.lastProgressTarget;
  }

  /** `samples`: the film's mean samples per pixel (FilmJob.meanSamples), `spp` by default. */
  info(spp: number, samples = spp): ProgressInfo {
    return {
      spp,
      samples,
      target: this.host.target(),
      raysPerSecond: this.rays.rate(performance.now()),
      noise: this.noise,
    };
  }

  fps(now: number): number {
    return this.frames.rate(now);
  }
}
