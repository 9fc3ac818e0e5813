/**
 * The log–log plot of error against tracing time: the relative RMS error
 * (√relMSE) estimated from the film's own variance, the true one against
 * the Mitsuba reference where the view has one, the true error of the denoised picture
 * (the Denoise switch) against the same reference, and a dashed line of slope
 * −½ (error ∝ 1/√t, what Monte Carlo promises) through the first estimate.
 * Drawn with Canvas 2D a few times a second; the numbers also go to a text
 * line (and the canvas's label) for screen readers.
 */

export interface ErrorPoint {
  /** Tracing seconds since the render started. */
  seconds: number;
  spp: number;
  /** relMSE estimated from per-pixel variance (NaN: not yet). */
  estimated: number;
  /** relMSE against the reference (NaN: no reference for this view). */
  truth: number;
  /** relMSE of the denoised picture against the reference (NaN: none at this point). */
  denoised: number;
}

const COLORS = {
  estimated: '#e0a84a',
  truth: '#5ec8e5',
  denoised: '#8fd16a',
  slope: '#9aa0a6',
  grid: 'rgba(255, 255, 255, 0.08)',
  label: '#9aa0a6',
};

/** A relative RMS error as the plot's caption and the stats' Noise write it. */
export function formatRelError(v: number): string {
  if (!Number.isFinite(v)) return '–';
  return v >= 0.01 ? v.toFixed(3) : v.toExponential(1);
}

/** Decades [10^a, 10^b] covering [lo, hi], at least one decade wide. */
function decades(lo: number, hi: number): [number, number] {
  let a = Math.floor(Math.log10(lo));
  let b = Math.ceil(Math.log10(hi));
  if (b - a < 1) b = a + 1;
  if (!Number.isFinite(a) || !Number.isFinite(b)) [a, b] = [-1, 0];
  return [a, b];
}

export class ErrorPlot {
  private readonly canvas: HTMLCanvasElement;
  private readonly caption: HTMLElement;

  constructor(canvas: HTMLCanvasElement, caption: HTMLElement) {
    this.canvas = canvas;
    this.caption = caption;
  }

  /** Redraws the plot and caption for `points`; `note` explains a missing true error. */
  draw(points: readonly ErrorPoint[], note: string): void {
    const canvas = this.canvas;
    const dpr = Math.min(2, devicePixelRatio || 1);
    const cssW = canvas.clientWidth || 260;
    const cssH = canvas.clientHeight || 150;
    if (canvas.width !== Math.round(cssW * dpr)) canvas.width = Math.round(cssW * dpr);
    if (canvas.height !== Math.round(cssH * dpr)) canvas.height = Math.round(cssH * dpr);
    const ctx = canvas.getContext('2d')!;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, cssW, cssH);

    const est = points.filter((p) => p.seconds > 0 && p.estimated > 0);
    const truth = points.filter((p) => p.seconds > 0 && p.truth > 0);
    const denoised = points.filter((p) => p.seconds > 0 && p.denoised > 0);
    const all = [
      ...est.map((p) => Math.sqrt(p.estimated)),
      ...truth.map((p) => Math.sqrt(p.truth)),
      ...denoised.map((p) => Math.sqrt(p.denoised)),
    ];
    const times = [...est, ...truth, ...denoised].map((p) => p.seconds);
    const last = points[points.length - 1];
    const lastEst = est[est.length - 1];
    const lastTruth = truth[truth.length - 1];
    const lastDenoised = denoised[denoised.length - 1];
    const denoisedText = lastDenoised
      ? `, denoised ${formatRelError(Math.sqrt(lastDenoised.denoised))} (from ${lastDenoised.spp} spp)`
      : '';
    this.caption.textContent =
      all.length === 0
        ? `Waiting for two samples per pixel… ${note}`
        : `At ${last.seconds.toFixed(1)} s (${last.spp} spp): estimated ${formatRelError(
            lastEst ? Math.sqrt(lastEst.estimated) : NaN,
          )}, true ${formatRelError(lastTruth ? Math.sqrt(lastTruth.truth) : NaN)}${denoisedText} (relative RMS error per cell, √relMSE). ${note}`;
    canvas.setAttribute('aria-label', `Error against time, log–log. ${this.caption.textContent}`);

    const left = 34;
    const right = 6;
    const top = 6;
    const bottom = 18;
    const w = cssW - left - right;
    const h = cssH - top - bottom;
    const [x0, x1] = decades(Math.min(...times, 1), Math.max(...times, 1));
    const [y0, y1] = decades(Math.min(...all, 0.1), Math.max(...all, 0.1));
    const px = (s: number) => left + ((Math.log10(s) - x0) / (x1 - x0)) * w;
    const py = (e: number) => top + (1 - (Math.log10(e) - y0) / (y1 - y0)) * h;

    ctx.font = '10px system-ui, sans-serif';
    ctx.lineWidth = 1;
    ctx.fillStyle = COLORS.label;
    ctx.strokeStyle = COLORS.grid;
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    for (let d = x0; d <= x1; d++) {
      const x = px(10 ** d);
      ctx.beginPath();
      ctx.moveTo(x, top);
      ctx.lineTo(x, top + h);
      ctx.stroke();
      ctx.fillText(d === x1 ? `${10 ** d} s` : String(10 ** d), x, top + h + 3);
    }
    ctx.textAlign = 'right';
    ctx.textBaseline = 'middle';
    for (let d = y0; d <= y1; d++) {
      const y = py(10 ** d);
      ctx.beginPath();
      ctx.moveTo(left, y);
      ctx.lineTo(left + w, y);
      ctx.stroke();
      ctx.fillText(d >= 0 ? String(10 ** d) : `1e${d}`, left - 3, y);
    }
    ctx.save();
    ctx.beginPath();
    ctx.rect(left, top, w, h);
    ctx.clip();
    if (est.length > 0) {
      // Slope −½ through the first estimate: where 1/√t would take it.
      const t0 = est[0].seconds;
      const e0 = Math.sqrt(est[0].estimated);
      ctx.setLineDash([4, 3]);
      ctx.strokeStyle = COLORS.slope;
      ctx.beginPath();
      ctx.moveTo(px(10 ** x0), py(e0 * Math.sqrt(t0 / 10 ** x0)));
      ctx.lineTo(px(10 ** x1), py(e0 * Math.sqrt(t0 / 10 ** x1)));
      ctx.stroke();
      ctx.setLineDash([]);
    }
    const line = (series: ErrorPoint[], value: (p: ErrorPoint) => number, color: string) => {
      if (series.length === 0) return;
      ctx.strokeStyle = color;
      ctx.fillStyle = color;
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      series.forEach((p, i) => {
        const x = px(p.seconds);
        const y = py(Math.sqrt(value(p)));
        if (i === 0) ctx.moveTo(x, y);
        else ctx.lineTo(x, y);
      });
      ctx.stroke();
      const p = series[series.length - 1];
      ctx.beginPath();
      ctx.arc(px(p.seconds), py(Math.sqrt(value(p))), 2.5, 0, 2 * Math.PI);
      ctx.fill();
    };
    line(est, (p) => p.estimated, COLORS.estimated);
    line(truth, (p) => p.truth, COLORS.truth);
    line(denoised, (p) => p.denoised, COLORS.denoised);
    ctx.restore();
  }
}
