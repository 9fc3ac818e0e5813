/**
 * How the controller runs and what it could not do, told as events: the
 * display and compute modes (with a `fallback` event when a lost WebGL2
 * context hands the picture to Canvas 2D and back), a full film smaller
 * than the canvas asks (the accumulator cap), and a film that could not be
 * made at all (an `error`).
 */
import type { Display } from './display.ts';
import { StandInDisplay } from './display-standin.ts';
import { FilmMemoryError, type Films } from './films.ts';
import type { FallbackInfo } from './types.ts';

export class Fallbacks {
  /** How it runs now: the display changes while a lost WebGL2 context is away. */
  mode: FallbackInfo;
  private readonly emit: (type: string, detail: unknown) => void;
  /** The accumulator-cap reason last reported with a `fallback` event (null: none). */
  private capReported: string | null = null;

  constructor(mode: FallbackInfo, emit: (type: string, detail: unknown) => void) {
    this.mode = mode;
    this.emit = emit;
  }

  /** Follows a stand-in display's moves between canvases; `onChange` then redraws and reports. */
  watch(display: Display, onChange: () => void): void {
    if (!(display instanceof StandInDisplay)) return;
    display.onChange = (_event, reason) => {
      this.mode = { ...this.mode, display: display.mode, reason };
      onChange();
    };
  }

  /** No film could be made (the accumulator cap, or no memory): said once, as an error. */
  filmFailed(e: unknown): void {
    if (!(e instanceof FilmMemoryError)) throw e;
    this.emit('error', { message: e.message });
  }

  /** A full film smaller than the canvas asks is reported once per size, as a fallback. */
  reportCap(films: Films): void {
    if (films.previewing) return;
    const cap = films.capped;
    const reason = cap?.reason ?? null;
    if (reason === this.capReported) return;
    this.capReported = reason;
    if (cap) this.emit('fallback', { ...this.mode, reason, renderScale: cap.scale });
  }
}
