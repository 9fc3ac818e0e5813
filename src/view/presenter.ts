/**
 * The picture on screen: uploads a film's changed rows to the display and
 * draws them at the current exposure, and keeps the backdrop (backdrop.ts),
 * the last picture, which the display shows wherever a restarted film has
 * no sample yet. While a denoised picture of the film is set (showDenoised), it is drawn
 * instead of the film's own sums, until it is dropped (a restart, denoising off).
 */
import { compositeBackdrop, type Backdrop } from './backdrop.ts';
import type { DenoisedImage } from './denoise-view.ts';
import type { Display, DisplayPixels } from './display.ts';
import type { FilmJob } from './film-job.ts';

export class Presenter {
  readonly display: Display;
  exposure: number;
  /** Exposure changed: redraw without new samples. */
  dirty = true;
  /** The last picture, shown where the active film has no sample yet. */
  private backdrop: Backdrop | null = null;
  /** The film the display showed last (its pixels are what is on screen). */
  private shownJob: FilmJob | null = null;
  /** The denoised picture drawn in place of the film's sums, and whether it is drawn yet. */
  private denoised: DenoisedImage | null = null;
  private denoisedNew = false;
  /** The display's texture holds something else than the film: upload every row next. */
  private uploadAll = false;

  constructor(display: Display, exposure: number) {
    this.display = display;
    this.exposure = exposure;
  }

  /** Bytes the backdrop holds. */
  get backdropBytes(): number {
    return this.backdrop?.rgba.byteLength ?? 0;
  }

  /** What is on screen (the shown film over the old backdrop) becomes the backdrop. */
  captureBackdrop(): void {
    const job = this.shownJob;
    if (!job) return;
    const d = this.denoisedFor(job);
    const sums = d ? d.sums : job.film.sums;
    this.backdrop = compositeBackdrop(sums, job.width, job.height, this.backdrop);
  }

  /** Shows `image` in place of the film of its size from the next present on. */
  showDenoised(image: DenoisedImage): void {
    this.denoised = image;
    this.denoisedNew = true;
  }

  /** Back to the film's own sums (a restart, or denoising turned off). */
  dropDenoised(): void {
    if (this.denoised === null) return;
    this.denoised = null;
    this.uploadAll = true;
    this.dirty = true;
  }

  /** A draw is owed now: the exposure changed, or a denoised picture is waiting. */
  get pending(): boolean {
    return this.dirty || this.denoisedNew;
  }

  /** The denoised picture on screen, if any. */
  get shownDenoised(): DenoisedImage | null {
    return this.denoised;
  }

  private denoisedFor(job: FilmJob): DenoisedImage | null {
    const d = this.denoised;
    return d && d.width === job.width && d.height === job.height ? d : null;
  }

  /**
   * Blanks the display after a reset, uploads the rows that changed since
   * the last draw and draws; with
   * `force`, draws even when nothing changed. Returns whether it drew.
   */
  present(job: FilmJob, force: boolean): boolean {
    const cleared = job.takeCleared();
    const dirty = job.takeDirtyRows();
    const d = this.denoisedFor(job);
    if (d) {
      // New samples wait under the denoised picture (the next one is made from them).
      if (!force && !cleared && !this.denoisedNew && !this.dirty) return false;
      this.display.draw(d.sums, job.width, job.height, this.exposure, null);
      this.denoisedNew = false;
      this.uploadAll = true;
    } else {
      if (!force && !cleared && dirty.length === 0 && !this.dirty) return false;
      if (cleared) this.display.clear(job.width, job.height, this.backdrop);
      this.display.draw(
        job.film.sums,
        job.width,
        job.height,
        this.exposure,
        this.uploadAll ? null : dirty,
      );
      this.uploadAll = false;
    }
    this.dirty = false;
    this.shownJob = job;
    return true;
  }

  /** The canvas's displayed pixels, `job` (the active film) redrawn first. */
  readPixels(job: FilmJob | null): DisplayPixels {
    // Drawn as a frame would be (only changed rows uploaded), so a read-back
    // checks the incremental upload too; WebGL2 needs the draw because its
    // buffer is not preserved after a frame is shown.
    if (job) this.present(job, true);
    return this.display.readPixels();
  }
}
