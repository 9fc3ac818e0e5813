/**
 * Feeds the error plot: a few times a second, when the browser is idle,
 * reads the full film in place (no copy), computes the estimated and, where
 * the view has a reference, the true relMSE on the comparison grid
 * (error-grid.ts) and adds a point; each new denoised picture (the Denoise
 * switch) adds a point with its true relMSE, on the same grid, at the
 * tracing time it appeared. A restart (any change of view or settings)
 * starts a new series. Nothing here runs on the tracing or
 * drawing path: the workers never wait for it, and a frame never does.
 */
import type { Controller } from '../view/index.ts';
import {
  errorFigures,
  gridLayout,
  gridStep,
  type GridLayout,
  type ReferenceLuminance,
} from './error-grid.ts';
import { ErrorPlot, type ErrorPoint } from './error-plot.ts';
import type { PresetName } from './presets.ts';
import { loadReference, referenceApplies, REFERENCE_SIZES } from './references.ts';

/** Points are taken at most this often. */
export const SAMPLE_MS = 250;
/** Series longer than this drop every other point (the plot is log-scaled in time anyway). */
const MAX_POINTS = 240;

export class ErrorMeter {
  /** The current series (read by the browser tests). */
  points: ErrorPoint[] = [];
  /** Why there is no true error for this view, in words ('' when there is one). */
  note = '';
  private readonly controller: Controller;
  private readonly plot: ErrorPlot;
  private version = -1;
  private lastSpp = -1;
  /** Samples of the last denoised picture measured (-1: none in this series). */
  private lastDenoisedSpp = -1;
  private preset: PresetName | null = null;
  private reference: ReferenceLuminance | null = null;
  private layoutKey = '';
  private layout: GridLayout | null = null;
  private timer: ReturnType<typeof setTimeout> | undefined;
  private stopped = false;

  /**
   * The latest estimated relative RMS error (√ of the estimated relMSE per cell), the
   * figure the plot's caption calls "estimated" and the stats call Noise; NaN: none yet.
   */
  get noise(): number {
    for (let i = this.points.length - 1; i >= 0; i--) {
      const e = this.points[i]!.estimated;
      if (e > 0) return Math.sqrt(e);
    }
    return NaN;
  }

  constructor(controller: Controller, plot: ErrorPlot) {
    this.controller = controller;
    this.plot = plot;
  }

  /** The scene now loaded is this preset (null: a scene without a reference). */
  setPreset(preset: PresetName | null): void {
    this.preset = preset;
    this.reference = null;
    this.version = -1;
    if (!preset) return;
    loadReference(preset).then(
      (ref) => {
        if (this.preset === preset) this.reference = ref;
      },
      () => {
        if (this.preset === preset) this.note = 'The reference image could not be loaded.';
      },
    );
  }

  start(): void {
    const tick = () => {
      if (this.stopped) return;
      this.sample();
      this.timer = setTimeout(schedule, SAMPLE_MS);
    };
    // Idle time first, so the measurement never delays a frame.
    const schedule = () =>
      typeof requestIdleCallback === 'function'
        ? requestIdleCallback(tick, { timeout: SAMPLE_MS })
        : tick();
    schedule();
  }

  stop(): void {
    this.stopped = true;
    clearTimeout(this.timer);
  }

  /** Takes one point now if the film has new samples. */
  sample(): void {
    const c = this.controller;
    const snap = c.filmSnapshot();
    const scene = c.scene;
    if (!snap || !scene) return;
    if (snap.version !== this.version) {
      this.version = snap.version;
      this.points = [];
      this.lastSpp = -1;
      this.lastDenoisedSpp = -1;
    }
    const d = c.denoisedSnapshot();
    const newDenoised = d !== null && d.version === snap.version && d.spp !== this.lastDenoisedSpp;
    if (snap.spp < 1 || (snap.spp === this.lastSpp && !newDenoised)) return;
    const newSamples = snap.spp !== this.lastSpp;
    this.lastSpp = snap.spp;

    const ref = this.preset ? this.reference : null;
    const [rw, rh] = ref
      ? [ref.width, ref.height]
      : this.preset
        ? REFERENCE_SIZES[this.preset]
        : [128, 128];
    const key = `${snap.width}x${snap.height}/${rw}x${rh}`;
    if (key !== this.layoutKey) {
      this.layoutKey = key;
      this.layout = gridLayout(snap.width, snap.height, rw, rh);
    }
    const layout = this.layout;
    let note = '';
    let useReference = false;
    if (!this.preset) note = 'This scene has no reference image: estimate only.';
    else if (!referenceApplies(scene, snap.camera, snap.bounces))
      note = `True error only for the scene's own view: Reset view, pinhole, ${scene.settings.maxBounces} bounces.`;
    else if (!layout)
      note = `True error needs a render height that is a multiple of ${gridStep(rw, rh)} pixels.`;
    else if (!ref) note = 'Loading the reference…';
    else useReference = true;
    this.note = note;
    if (!layout) {
      this.plot.draw(this.points, note);
      return;
    }
    if (newSamples) {
      const f = errorFigures(snap.width, snap.sums, snap, layout, useReference ? ref : null);
      this.points.push({
        seconds: snap.seconds,
        spp: snap.spp,
        estimated: f.estimatedRelMse,
        truth: f.relMse,
        denoised: NaN,
      });
    }
    if (newDenoised && d.width === snap.width && d.height === snap.height) {
      this.lastDenoisedSpp = d.spp;
      // One sample a pixel (A = 1): the figures read no squares then.
      const f = errorFigures(d.width, d.sums, d.sums, layout, useReference ? ref : null);
      this.points.push({
        seconds: d.seconds,
        spp: d.spp,
        estimated: NaN,
        truth: NaN,
        denoised: f.relMse,
      });
    }
    if (this.points.length > MAX_POINTS) {
      this.points = this.points.filter((_, i) => i % 2 === 0 || i === this.points.length - 1);
    }
    this.plot.draw(this.points, note);
  }
}
