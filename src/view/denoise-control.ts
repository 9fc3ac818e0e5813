/**
 * The denoiser's part in a controller: the switch (PathTracerOptions.denoise,
 * setDenoise), what it changes in the films (albedo and normal planes; the automatic
 * scale's pixel cap, auto-scale.ts DENOISE_BUDGET_MS) and the denoised pictures
 * (denoise-view.ts) on their way to the screen.
 */
import { denoisePixelCap, RESCALE_MIN_GAIN } from './auto-scale.ts';
import { ViewDenoiser, type DenoisedImage } from './denoise-view.ts';
import type { Films } from './films.ts';
import type { FirstPass } from './first-pass.ts';
import type { Presenter } from './presenter.ts';
import type { DenoisedInfo } from './types.ts';

export interface DenoiseControlHost {
  films: Films;
  firstPass: FirstPass;
  screen: Presenter;
  /** A new configuration version and reset (Controller.restart). */
  restart(): void;
  wake(): void;
  emit(type: 'denoised' | 'error', detail: DenoisedInfo | { message: string }): void;
  /** The film's tracing seconds now. */
  seconds(now: number): number;
}

export class DenoiseControl {
  readonly denoiser: ViewDenoiser;
  private readonly host: DenoiseControlHost;
  /** The denoiser's warm cost per pixel on this machine (NaN: not measured yet). */
  private msPerPixel = NaN;
  /** The automatic scale followed the measured cost in this scene. */
  private scaled = false;

  /** `workers`: denoise threads (PathTracerOptions.denoiseWorkers; default from the cores). */
  constructor(on: boolean, host: DenoiseControlHost, workers?: number) {
    this.host = host;
    host.films.aux = on;
    host.films.maxAutoPixels = on ? denoisePixelCap() : Infinity;
    this.denoiser = new ViewDenoiser(
      on,
      {
        show: (image) => {
          host.screen.showDenoised(image);
          const { spp, width, height, ms, sinceRestartMs } = image;
          host.emit('denoised', { spp, width, height, ms, sinceRestartMs });
          host.wake();
          // After the event: a rescale it causes restarts, and drops this picture.
          this.measured(image);
        },
        // The denoiser stopped (it switched itself off): the film's own picture again.
        error: (message) => {
          host.screen.dropDenoised();
          host.emit('error', { message });
          host.wake();
        },
        seconds: (now) => host.seconds(now),
      },
      workers,
    );
  }

  get on(): boolean {
    return this.denoiser.enabled;
  }

  /** A new scene: the measured cost may move the scale once more. */
  sceneLoaded(): void {
    this.scaled = false;
  }

  /** The film started over (restart or reset): the picture on screen and in progress go. */
  restarted(now: number): void {
    this.host.screen.dropDenoised();
    this.denoiser.restarted(now);
  }

  /** Each frame while the full film rests at `spp`: true while a picture is due or coming. */
  update(spp: number, target: number): boolean {
    const full = this.host.films.full;
    return full !== null && this.denoiser.update(full, spp, target);
  }

  set(on: boolean): void {
    if (on === this.denoiser.enabled) return;
    const { films, screen } = this.host;
    // Films made from now on record albedo and normal only while denoising is on; a
    // full film without them is remade (a restart) when it is turned on.
    films.aux = on;
    films.maxAutoPixels = on
      ? denoisePixelCap(this.msPerPixel > 0 ? this.msPerPixel : undefined)
      : Infinity;
    if (on) this.denoiser.enable();
    else {
      this.denoiser.disable();
      screen.dropDenoised();
    }
    this.rescale(on);
  }

  /** The automatic scale chosen again (the pixel cap changed); restarts when the film must change. */
  private rescale(needAux: boolean): void {
    const { films, firstPass } = this.host;
    if (films.autoScale && firstPass.rate > 0)
      films.renderScale = firstPass.scaleFor(firstPass.rate);
    const full = films.full;
    if (!full || films.previewing || firstPass.active) {
      this.host.wake();
      return;
    }
    const [w, h] = films.fullSize();
    if (full.width !== w || full.height !== h || (needAux && !full.aux)) this.host.restart();
    else this.host.wake();
  }

  /**
   * After a denoised picture: its cost per pixel, once warm (from the second picture on),
   * becomes the automatic scale's budget, once a scene, when it moves the cap by at
   * least RESCALE_MIN_GAIN (a faster or slower machine than the default assumes).
   */
  private measured(image: DenoisedImage): void {
    if (this.denoiser.count < 2) return;
    const cost = image.ms / (image.width * image.height);
    this.msPerPixel = this.msPerPixel > 0 ? Math.min(this.msPerPixel, cost) : cost;
    const films = this.host.films;
    if (this.scaled || !films.autoScale) return;
    this.scaled = true;
    const cap = denoisePixelCap(this.msPerPixel);
    const ratio = cap / films.maxAutoPixels;
    if (ratio < RESCALE_MIN_GAIN && ratio > 1 / RESCALE_MIN_GAIN) return;
    films.maxAutoPixels = cap;
    this.rescale(true);
  }

  /** The picture on screen with the configuration version it belongs to (null: none). */
  snapshot(version: number): (DenoisedImage & { version: number }) | null {
    const d = this.host.screen.shownDenoised;
    return d && !this.host.films.previewing ? { ...d, version } : null;
  }

  /** For the stats: the samples and network time of the picture on screen. */
  info(): { spp: number; ms: number } | null {
    const d = this.host.screen.shownDenoised;
    return d ? { spp: d.spp, ms: d.ms } : null;
  }

  destroy(): void {
    this.denoiser.destroy();
  }
}
