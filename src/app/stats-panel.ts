/**
 * The live numbers: samples per pixel with a progress bar toward the
 * target, FPS, M rays/s, main-thread frame time, resolution, memory and
 * the noise estimate. Refreshed a few times a second, not every frame.
 */
import type { Controller } from '../view/index.ts';
import { formatBytes, formatNoise, formatRate } from './format.ts';

const REFRESH_MS = 250;

function text(id: string, value: string): void {
  const el = document.getElementById(id);
  if (el && el.textContent !== value) el.textContent = value;
}

export function startStatsPanel(getController: () => Controller): () => void {
  const bar = document.getElementById('progress-bar') as HTMLElement;
  const timer = setInterval(() => {
    const c = getController();
    const s = c.stats();
    const done = s.spp >= s.target;
    text('s-spp', `${s.spp} / ${s.target}${done ? ' (done)' : s.paused ? ' (paused)' : ''}`);
    text('s-fps', s.fps > 0 ? s.fps.toFixed(0) : '–');
    text('s-rays', done || s.paused ? '–' : formatRate(s.raysPerSecond));
    text('s-frame', `${s.frameMs.toFixed(2)} ms`);
    text('s-res', `${s.width} × ${s.height}`);
    text('s-mem', formatBytes(s.memoryBytes));
    text('s-noise', formatNoise(s.noise));
    bar.style.width = `${Math.min(100, (c.progress() / s.target) * 100).toFixed(2)}%`;
  }, REFRESH_MS);
  return () => clearInterval(timer);
}
