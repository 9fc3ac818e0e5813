/**
 * The demo page: the Cornell box renders at once; presets, scene files,
 * camera controls, settings, stats, the error plot, saving and a benchmark
 * around one controller from src/view.
 */
import { validateScene } from '../core/index.ts';
import { createPathTracer, type LoadProgressInfo } from '../view/index.ts';
import { currentPool } from '../view/pool.ts';
import { faults } from '../view/worker-deaths.ts';
import { BENCHMARK_SECONDS, BENCHMARK_WARMUP_S, runBenchmark } from './benchmark.ts';
import { attachControls } from './controls.ts';
import { gridStep } from './error-grid.ts';
import { ErrorMeter } from './error-meter.ts';
import { ErrorPlot } from './error-plot.ts';
import { readParams } from './params.ts';
import { PRESETS, PRESET_FILES, type PresetName } from './presets.ts';
import { REFERENCE_SIZES } from './references.ts';
import { attachSceneFiles } from './scene-file.ts';
import { startStatsPanel } from './stats-panel.ts';
import './style.css';

const { preset, options, unknownScene, benchmarkSeconds } = readParams(location.search);
const canvas = document.getElementById('view') as HTMLCanvasElement;
if (options.width && options.height) {
  // A fixed render size (tests, benchmarks) keeps its own aspect ratio on screen.
  canvas.classList.add('fixed');
  canvas.style.aspectRatio = `${options.width} / ${options.height}`;
}

/** Render-height step under which the film tiles the preset's reference grid (error-grid.ts). */
function sizeStepFor(name: PresetName | null): number {
  return name ? gridStep(...REFERENCE_SIZES[name]) : gridStep(128, 128);
}

const controller = createPathTracer(canvas, {
  ...options,
  scene: PRESETS[preset],
  files: PRESET_FILES,
  sizeStep: sizeStepFor(preset),
});

const errorBox = document.getElementById('error') as HTMLElement;
function showError(message: string | null): void {
  errorBox.hidden = message === null;
  errorBox.textContent = message ?? '';
}
errorBox.addEventListener('click', () => showError(null));
/** Load progress of a model, then what its files use that pathwise ignores. */
const noticeBox = document.getElementById('notice') as HTMLElement;
function showNotice(message: string | null): void {
  noticeBox.hidden = message === null;
  noticeBox.textContent = message ?? '';
}
noticeBox.addEventListener('click', () => showNotice(null));
if (unknownScene !== null) {
  showError(
    `There is no scene "${unknownScene}" (the scene URL parameter takes ${Object.keys(PRESETS).join(', ')}); showing the Cornell box.`,
  );
}

const meter = new ErrorMeter(
  controller,
  new ErrorPlot(
    document.getElementById('error-plot') as HTMLCanvasElement,
    document.getElementById('error-caption') as HTMLElement,
  ),
);

// Test hook for the browser tests (tests/browser): the controller, the
// error meter, the factory so a test can put a second view on the page, and
// the worker pool's fault hooks with the page's fault counts.
(window as unknown as { __pathwise: unknown }).__pathwise = {
  controller,
  createPathTracer,
  errorMeter: meter,
  pool: currentPool,
  faults,
};

/**
 * A loaded scene is a preset when it is one exactly (a file may share a preset's name
 * only). Decoded meshes and maps are left out of the comparison: the preset is the same
 * before and after its files are read, and a big mesh is not turned into text.
 */
const sceneKey = (scene: unknown) =>
  JSON.stringify(scene, (k, v) =>
    k === 'data' || k === 'image' || ArrayBuffer.isView(v) ? undefined : v,
  );
const presetKeys = new Map(
  (Object.keys(PRESETS) as PresetName[]).map((p) => [sceneKey(validateScene(PRESETS[p])), p]),
);
/** Shapes of the largest preset: a scene with more is none of them (and is not stringified). */
const presetShapes = Math.max(
  ...(Object.keys(PRESETS) as PresetName[]).map((p) => validateScene(PRESETS[p]).shapes.length),
);

const controls = attachControls(controller);
controls.sync();
const STAGES: Record<LoadProgressInfo['stage'], string> = {
  read: 'reading files',
  parse: 'parsing',
  textures: 'decoding textures',
  geometry: 'building geometry',
  compile: 'building the BVH',
};
controller.addEventListener('loadprogress', (e) => {
  const { stage, done, total } = (e as CustomEvent<LoadProgressInfo>).detail;
  showNotice(`Loading: ${STAGES[stage]}${total > 1 ? ` ${done}/${total}` : ''}`);
});
controller.addEventListener('load', (e) => {
  const { warnings } = (e as CustomEvent<{ warnings: string[] }>).detail;
  showNotice(warnings.length > 0 ? `Note: ${warnings.join('; ')}` : null);
  const scene = controller.scene;
  const name =
    scene && scene.shapes.length <= presetShapes ? (presetKeys.get(sceneKey(scene)) ?? null) : null;
  // Before the quick first pass ends and sizes the film.
  controller.setSizeStep(sizeStepFor(name));
  meter.setPreset(name);
  controls.sync();
  const title = scene?.name ?? '';
  document.title = title ? `${title} — pathwise` : 'pathwise';
  canvas.setAttribute('aria-label', `${title || 'Scene'}, path-traced image`);
});
controller.addEventListener('error', (e) => {
  showNotice(null);
  showError((e as CustomEvent<{ message: string }>).detail.message);
});
meter.start();

const mode = document.getElementById('mode') as HTMLElement;
function showMode(): void {
  const m = controller.mode;
  mode.textContent = `Display: ${m.display === 'webgl2' ? 'WebGL2' : 'Canvas 2D'} · Compute: ${
    m.compute === 'shared' ? 'shared memory' : 'transferred stripes'
  } — ${m.reason}.`;
}
showMode();
// The display changes while a lost WebGL2 context is away (and when it is back).
controller.addEventListener('fallback', showMode);

for (const button of document.querySelectorAll<HTMLButtonElement>('[data-preset]')) {
  button.addEventListener('click', () => {
    showError(null);
    void controller.setScene(PRESETS[button.dataset.preset as PresetName], PRESET_FILES);
  });
}

const fileInput = document.getElementById('file') as HTMLInputElement;
document.getElementById('open-scene')!.addEventListener('click', () => fileInput.click());
attachSceneFiles(
  () => controller,
  fileInput,
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

const panel = startStatsPanel(
  () => controller,
  () => meter.noise,
  controls.refresh,
);

const benchButton = document.getElementById('benchmark') as HTMLButtonElement;
const benchResult = document.getElementById('bench-result') as HTMLElement;
const benchSeconds = benchmarkSeconds ?? BENCHMARK_SECONDS;
benchButton.textContent = `Benchmark (${benchSeconds} s)`;
benchButton.addEventListener('click', async () => {
  benchButton.disabled = true;
  benchResult.textContent = `Running for ${benchSeconds} seconds on the Cornell box…`;
  panel.benchmark(benchSeconds + BENCHMARK_WARMUP_S);
  try {
    const r = await runBenchmark(controller, benchSeconds);
    benchResult.textContent =
      `Benchmark: ${r.mraysPerSecond.toFixed(2)} M rays/s · ${r.spp} spp at ${r.width}×${r.height} · ` +
      `${r.workers} workers · ${r.cores || '?'} cores reported by the browser`;
    benchResult.dataset.mrays = String(r.mraysPerSecond);
  } catch (e) {
    benchResult.textContent = `Benchmark failed: ${e instanceof Error ? e.message : String(e)}`;
  } finally {
    panel.benchmark(null);
    benchButton.disabled = false;
    controls.sync();
  }
});

const about = document.getElementById('about') as HTMLDialogElement;
document.getElementById('about-open')!.addEventListener('click', () => about.showModal());
