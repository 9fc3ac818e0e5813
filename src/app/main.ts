/**
 * The demo page: the Cornell box renders at once; presets, scene files,
 * camera controls, settings, stats, saving and a benchmark around one
 * controller from src/view.
 */
import { createPathTracer } from '../view/index.ts';
import { runBenchmark } from './benchmark.ts';
import { attachControls } from './controls.ts';
import { readParams } from './params.ts';
import { PRESETS, PRESET_FILES, type PresetName } from './presets.ts';
import { attachSceneFiles } from './scene-file.ts';
import { startStatsPanel } from './stats-panel.ts';
import './style.css';

const { preset, options } = readParams(location.search);
const canvas = document.getElementById('view') as HTMLCanvasElement;
if (options.width && options.height) {
  // A fixed render size (tests, benchmarks) keeps its own aspect ratio on screen.
  canvas.classList.add('fixed');
  canvas.style.aspectRatio = `${options.width} / ${options.height}`;
}
const controller = createPathTracer(canvas, {
  ...options,
  scene: PRESETS[preset],
  files: PRESET_FILES,
});

// Test hook for the browser tests (tests/browser): the controller, and the
// factory so a test can put a second view on the page (the shared pool).
(window as unknown as { __pathwise: unknown }).__pathwise = { controller, createPathTracer };

const errorBox = document.getElementById('error') as HTMLElement;
function showError(message: string | null): void {
  errorBox.hidden = message === null;
  errorBox.textContent = message ?? '';
}
errorBox.addEventListener('click', () => showError(null));

const controls = attachControls(controller, options.renderScale ?? 1);
controls.sync();
controller.addEventListener('load', () => {
  controls.sync();
  const name = controller.scene?.name ?? '';
  document.title = name ? `${name} — pathwise` : 'pathwise';
});
controller.addEventListener('error', (e) =>
  showError((e as CustomEvent<{ message: string }>).detail.message),
);

const mode = document.getElementById('mode') as HTMLElement;
const m = controller.mode;
mode.textContent = `Display: ${m.display === 'webgl2' ? 'WebGL2' : 'Canvas 2D'} · Compute: ${
  m.compute === 'shared' ? 'shared memory' : 'transferred stripes'
} — ${m.reason}.`;

for (const button of document.querySelectorAll<HTMLButtonElement>('[data-preset]')) {
  button.addEventListener('click', () => {
    showError(null);
    void controller.setScene(PRESETS[button.dataset.preset as PresetName], PRESET_FILES);
  });
}

attachSceneFiles(
  () => controller,
  document.getElementById('file') as HTMLInputElement,
  document.getElementById('stage') as HTMLElement,
  document.getElementById('drop-hint') as HTMLElement,
  () => showError(null),
  showError,
);

function download(data: Blob, name: string): void {
  const url = URL.createObjectURL(data);
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}
const baseName = () =>
  (controller.scene?.name || 'pathwise').replace(/[^\w-]+/g, '-').toLowerCase();
document.getElementById('save-png')!.addEventListener('click', () => {
  void controller.toBlob().then((b) => download(b, `${baseName()}.png`));
});
document.getElementById('save-pfm')!.addEventListener('click', () => {
  const bytes = controller.toPFM();
  download(new Blob([bytes.slice().buffer]), `${baseName()}.pfm`);
});

const benchButton = document.getElementById('benchmark') as HTMLButtonElement;
const benchResult = document.getElementById('bench-result') as HTMLElement;
benchButton.addEventListener('click', async () => {
  benchButton.disabled = true;
  benchResult.textContent = 'Running for 10 seconds on the Cornell box…';
  try {
    const r = await runBenchmark(controller);
    benchResult.textContent =
      `${r.mraysPerSecond.toFixed(2)} M rays/s · ${r.spp} spp at ${r.width}×${r.height} · ` +
      `${r.workers} workers · ${r.cores || '?'} cores reported by the browser`;
    benchResult.dataset.mrays = String(r.mraysPerSecond);
  } catch (e) {
    benchResult.textContent = `Benchmark failed: ${e instanceof Error ? e.message : String(e)}`;
  } finally {
    benchButton.disabled = false;
    controls.sync();
  }
});

const about = document.getElementById('about') as HTMLDialogElement;
document.getElementById('about-open')!.addEventListener('click', () => about.showModal());

startStatsPanel(() => controller);
