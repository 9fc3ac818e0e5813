/**
 * The picture on screen: uploads a film's changed rows to the display and
 * draws them at the current exposure, and keeps the backdrop (backdrop.ts),
 * the last picture, which the display shows wherever a restarted film has
 * no sample yet.
 */
import { compositeBackdrop, type Backdrop } from './backdrop.ts';
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
    this.backdrop = compositeBackdrop(job.film.sums, job.width, job.height, this.backdrop);
  }

  /**
   * Blanks the display after a reset, uploads the rows that changed since
   * the last draw and draws; with
   * `force`, draws even when nothing changed. Returns whether it drew.
   */
  present(job: FilmJob, force: boolean): boolean {
    const cleared = job.takeCleared();
    const dirty = job.takeDirtyRows();
    if (!force && !cleared && dirty.length === 0 && !this.dirty) return false;
    if (cleared) this.display.clear(job.width, job.height, this.backdrop);
    this.display.draw(job.film.sums, job.width, job.height, this.exposure, dirty);
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
