/**
 * The animation-frame loop. Each frame lets the film follow the canvas's
 * size, lets the quick first pass hand over to another film, uploads and
 * draws what the workers traced, and reports progress.
 *
 * The loop runs only while something can change on screen: samples
 * arriving, a pending resize, a redraw asked for. Paused, converged or in a
 * hidden tab it stops asking for frames (a page of idle views costs
 * nothing), and every call that can change the picture wakes it again.
 *
 * While the view rests and the film has two whole passes, new samples are drawn
 * at most every REST_DRAW_MS: each draw costs the page's thread an upload
 * and a composite of the whole canvas (in software, 0.4–0.5 of a core at
 * 40–60 fps on a 2-core machine, taken from the render workers), and a
 * picture refining ten times a second looks no different. Dragging, the
 * first pass after a restart, an exposure change and a new denoised picture
 * are drawn at once.
 *
 * An adaptive film's pilot gate (pilot-gate.ts) is checked each frame and, while it is
 * closed and the render is to pass it, by a timer too: a hidden tab runs no animation
 * frames but its workers go on, and would otherwise wait at the end of the pilot until
 * the tab is shown.
 */
import { ADAPTIVE_PILOT } from '../core/index.ts';
import type { Fallbacks } from './fallbacks.ts';
import type { Films } from './films.ts';
import type { FirstPass } from './first-pass.ts';
import type { Presenter } from './presenter.ts';
import type { ProgressMeter } from './progress-meter.ts';

/** What the loop reads from the controller each frame. */
export interface LoopHost {
  destroyed(): boolean;
  target(): number;
  paused(): boolean;
  /** The pointer (or keyboard) is moving the camera. */
  interacting(): boolean;
  /** The least time between draws of new samples while the view rests (REST_DRAW_MS). */
  restDrawMs(): number;
  /** A new configuration version and reset of the active film (Controller.restart). */
  restart(): void;
  /** Asks the pool's workers to look for work (an adaptive film's pilot gate opened). */
  wakeWorkers(): void;
  /**
   * The full film rests at `spp` samples: a denoised picture may be due
   * (denoise-view.ts). True while one is in flight or due.
   */
  denoise(spp: number): boolean;
}

/** The least time between draws of new samples while the view rests (PathTracerOptions.restDrawMs). */
export const REST_DRAW_MS = 100;
/** How often the pilot gate is checked besides the frames (a hidden tab has none). */
const PILOT_CHECK_MS = 250;

export class FrameLoop {
  private readonly host: LoopHost;
  private readonly films: Films;
  private readonly firstPass: FirstPass;
  private readonly screen: Presenter;
  private readonly meter: ProgressMeter;
  private readonly fallbacks: Fallbacks;
  /** The pending animation frame; 0 while the loop is idle. */
  private raf = 0;
  /** Animation frames the loop has run (see Controller.framesRun). */
  count = 0;
  /** When the picture was last drawn (frame time). */
  private lastDraw = -Infinity;
  /** The pending check of the pilot gate; 0 when none. */
  private pilotTimer: ReturnType<typeof setTimeout> | 0 = 0;

  constructor(
    host: LoopHost,
    films: Films,
    firstPass: FirstPass,
    screen: Presenter,
    meter: ProgressMeter,
    fallbacks: Fallbacks,
  ) {
    this.host = host;
    this.films = films;
    this.firstPass = firstPass;
    this.screen = screen;
    this.meter = meter;
    this.fallbacks = fallbacks;
  }

  /**
   * Makes sure an animation frame is coming (the loop stops itself when idle), and that
   * a closed pilot gate is watched even where no frame comes (a hidden tab).
   */
  wake(): void {
    if (this.host.destroyed()) return;
    this.watchPilot();
    if (this.raf !== 0) return;
    this.raf = requestAnimationFrame(this.frame);
  }

  /** Cancels the pending frame (destroy). */
  stop(): void {
    cancelAnimationFrame(this.raf);
    this.raf = 0;
    clearTimeout(this.pilotTimer);
    this.pilotTimer = 0;
  }

  /** Opens the active film's pilot gate when its pilot is done; keeps a timer on it while closed. */
  private checkPilot(): void {
    const job = this.films.active();
    if (!job || this.host.destroyed()) return;
    if (job.advance()) {
      this.host.wakeWorkers();
      this.wake();
    }
    this.watchPilot();
  }

  /**
   * Arms the gate's timer while the active film's pilot is under way and will end: not
   * paused, and a target past the pilot (at or below it the gate never has to open, and
   * an idle view costs nothing). Every change that can restart the film wakes the loop,
   * and so comes here.
   */
  private watchPilot(): void {
    const job = this.films.active();
    if (this.pilotTimer !== 0 || !job?.pilotPending) return;
    if (this.host.paused() || this.host.target() <= ADAPTIVE_PILOT) return;
    this.pilotTimer = setTimeout(() => {
      this.pilotTimer = 0;
      this.checkPilot();
    }, PILOT_CHECK_MS);
  }

  private readonly frame = (now: number): void => {
    const { host, films, firstPass, meter } = this;
    this.raf = 0;
    if (host.destroyed()) return;
    this.count++;
    try {
      if (films.follow(now, host.target())) host.restart();
    } catch (e) {
      this.fallbacks.filmFailed(e);
    }
    // The speed measurements may hand over to another film (a restart):
    // this frame then draws that one, over the picture captured as backdrop.
    const before = films.active();
    const paused = host.paused();
    if (before && firstPass.advance(now, before, host.target(), paused, host.interacting())) {
      host.restart();
    }
    const job = films.active();
    // No scene yet: setScene's restart wakes the loop. A resize waiting to
    // settle is checked again on the next frame.
    if (!job) {
      if (films.resizePending) this.wake();
      return;
    }
    // An adaptive film whose pilot is done: the map is built and passes past it may start.
    this.checkPilot();
    const segments = job.takeSegments();
    meter.traced(now, segments);
    // Preview passes are not the image's samples: the full film has none yet.
    const spp = films.previewing ? 0 : job.passesDone();
    // From the second pass on (the first whole image is drawn the frame it completes),
    // and not the last one or a paused render's (their frames are the loop's last).
    const resting =
      !films.previewing && !host.interacting() && spp >= 2 && spp < host.target() && !host.paused();
    const held = resting && !this.screen.pending && now - this.lastDraw < host.restDrawMs();
    const t0 = performance.now();
    const drew = !held && this.screen.present(job, false);
    if (drew) {
      this.lastDraw = now;
      meter.drew(now, performance.now() - t0);
    }
    if (drew) firstPass.drew(now, job, spp);
    meter.update(now, job, spp);
    const denoising = !films.previewing && !host.interacting() && host.denoise(spp);
    // Another frame only while the picture can still change: samples are
    // (or may soon be) arriving, a draw or an event is owed, a resize is
    // settling or the pointer drags the preview.
    const tracing = !host.paused() && spp < host.target();
    const owed = meter.owed(spp) || this.screen.dirty;
    if (
      drew ||
      held ||
      denoising ||
      segments > 0 ||
      tracing ||
      owed ||
      job.busy() ||
      (firstPass.active && !host.paused()) ||
      films.resizePending ||
      films.wantPreview ||
      films.previewing
    ) {
      this.wake();
    }
  };
}
