/**
 * The live numbers: samples per pixel with a progress bar toward the
 * target, FPS, M rays/s, main-thread frame time, resolution, memory, the
 * noise estimate and the denoised picture's samples. Noise is the error
 * plot's own estimate (ErrorMeter.noise: the relative RMS error per grid
 * cell, √ of the estimated relMSE), written as the plot's caption writes it,
 * so the two numbers on the page are one figure. Refreshed a few times a second, not every frame.
 * While the benchmark runs, progress is its elapsed time, not samples
 * toward the (deliberately unreachable) target it sets.
 */
import type { Controller } from '../view/index.ts';
import { formatRelError } from './error-plot.ts';
import { formatBytes, formatRate } from './format.ts';

const REFRESH_MS = 250;

function text(id: string, value: string): void {
  const el = document.getElementById(id);
  if (el && el.textContent !== value) el.textContent = value;
}

export interface StatsPanel {
  /** A benchmark runs from now for `seconds` (null: it ended). */
  benchmark(seconds: number | null): void;
  stop(): void;
}

export function startStatsPanel(
  getController: () => Controller,
  noise: () => number,
  onTick?: () => void,
): StatsPanel {
  const bar = document.getElementById('progress-bar') as HTMLElement;
  let bench: { start: number; seconds: number } | null = null;
  const timer = setInterval(() => {
    const c = getController();
    const s = c.stats();
    let fraction: number;
    if (bench) {
      const elapsed = Math.min(bench.seconds, (performance.now() - bench.start) / 1000);
      text('s-spp', `${s.spp} (benchmark, ${elapsed.toFixed(0)} of ${bench.seconds} s)`);
      fraction = elapsed / bench.seconds;
    } else {
      const done = s.spp >= s.target;
      // Past an adaptive render's pilot, passes and samples part: the mean says how many.
      const mean = s.samples < s.spp ? `, mean ${s.samples.toFixed(0)}` : '';
      const state = done ? ' (done)' : s.paused ? ' (paused)' : '';
      text('s-spp', `${s.spp} / ${s.target}${mean}${state}`);
      fraction = c.progress() / s.target;
    }
    const idle = (!bench && s.spp >= s.target) || s.paused;
    text('s-fps', s.fps > 0 ? s.fps.toFixed(0) : '–');
    text('s-rays', idle ? '–' : formatRate(s.raysPerSecond));
    text('s-frame', `${s.frameMs.toFixed(2)} ms`);
    text('s-res', `${s.width} × ${s.height}`);
    text('s-mem', formatBytes(s.memoryBytes));
    text('s-noise', formatRelError(noise()));
    text(
      's-denoised',
      s.denoised
        ? `from ${s.denoised.spp} spp (${(s.denoised.ms / 1000).toFixed(2)} s)`
        : c.denoise
          ? 'when the view rests'
          : 'off',
    );
    bar.style.width = `${Math.min(100, fraction * 100).toFixed(2)}%`;
    onTick?.();
  }, REFRESH_MS);
  return {
    benchmark(seconds) {
      bench = seconds === null ? null : { start: performance.now(), seconds };
    },
    stop: () => clearInterval(timer),
  };
}
