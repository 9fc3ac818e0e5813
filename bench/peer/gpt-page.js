// The page side of the peer benchmark for three-gpu-pathtracer: bundled by
// run.mjs with esbuild and opened in the same headless Chromium as pathwise's
// demo. `window.runPeer(config)` renders a pathwise scene file with
// WebGLPathTracer and keeps copies of its float accumulation (before any tone
// mapping) at sample-count checkpoints, with the page clock at each.
import { WebGLRenderer } from 'three';
import { WebGLPathTracer } from 'three-gpu-pathtracer';
import { threeSceneFromPathwise } from './three-scene.js';

const now = () => performance.now();
/** Lets the event loop run (the compile's polling, Playwright's calls) between samples. */
const yieldTask = () => new Promise((resolve) => setTimeout(resolve, 0));

function glInfo(gl) {
  const debug = gl.getExtension('WEBGL_debug_renderer_info');
  return {
    renderer: gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER),
    version: gl.getParameter(gl.VERSION),
    floatBlend: !!gl.getExtension('EXT_float_blend'),
    colorBufferFloat: !!gl.getExtension('EXT_color_buffer_float'),
    parallelCompile: !!gl.getExtension('KHR_parallel_shader_compile'),
  };
}

/**
 * relMSE as bench/lib.mjs defines it, against the reference (top-down RGB),
 * of a bottom-up RGBA image. The page uses it only to decide when to stop;
 * run.mjs recomputes every reported value with lib.mjs's own function.
 */
function relMseBottomUp(rgba, ref, width, height) {
  let s = 0;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = ((height - 1 - y) * width + x) * 4;
      const j = (y * width + x) * 3;
      for (let c = 0; c < 3; c++) {
        const d = rgba[i + c] - ref[j + c];
        s += (d * d) / (ref[j + c] * ref[j + c] + 0.01);
      }
    }
  }
  return s / ref.length;
}

/**
 * config: { scene (pathwise JSON), width, height, bounces, tiles, checkpoints
 * (ascending sample counts), capMs (stop after this long since navigation),
 * reference (top-down RGB array), stopRelMse (stop once reached) }.
 * Returns the timeline (page clock, ms since navigation start) and the images.
 */
window.runPeer = async function runPeer(config) {
  const t = { start: now() };
  const warnings = [];
  const origWarn = console.warn;
  console.warn = (...args) => {
    warnings.push(args.map(String).join(' '));
    origWarn(...args);
  };
  const { width, height } = config;
  const ref = Float32Array.from(config.reference);
  const canvas = document.createElement('canvas');
  document.body.appendChild(canvas);
  const renderer = new WebGLRenderer({ canvas, antialias: false });
  renderer.setPixelRatio(1);
  renderer.setSize(width, height, false);
  const gl = renderer.getContext();
  const info = glInfo(gl);
  t.context = now();

  const { scene, camera, summary } = threeSceneFromPathwise(config.scene, width, height, {
    emitters: config.emitters,
  });
  const pt = new WebGLPathTracer(renderer);
  // Render every sample into the float target at once: no delay, no fade, no
  // rasterised stand-in, no low-resolution preview, nothing drawn to the
  // canvas (the accumulation is read, not displayed).
  pt.renderDelay = 0;
  pt.minSamples = 0;
  pt.fadeDuration = 0;
  pt.dynamicLowRes = false;
  pt.rasterizeScene = false;
  pt.renderToCanvas = false;
  pt.tiles.set(config.tiles, config.tiles);
  pt.bounces = config.bounces;
  if (config.mis === false) pt.multipleImportanceSampling = false;
  // NEE is on by default (FEATURE_MIS) but samples only light objects; the
  // scene has none, so the emissive quad is reached by BSDF sampling alone.
  pt.setScene(scene, camera);
  t.sceneBuilt = now();

  const readBack = () => {
    const target = pt.target;
    const buffer = new Float32Array(target.width * target.height * 4);
    renderer.readRenderTargetPixels(target, 0, 0, target.width, target.height, buffer);
    return buffer;
  };

  // Compilation: setScene sets defines and the material compiles
  // asynchronously (KHR_parallel_shader_compile); renderSample skips tracing
  // while it runs. The first sample is timed until its pixels are read back.
  const checkpoints = [];
  let next = 0;
  let readMs = 0;
  // At most two samples in flight: renderSample only queues the draw, and a
  // deep queue would run far past the time cap before a readback drained it.
  const fences = [];
  for (;;) {
    while (fences.length >= 2) {
      if (gl.getSyncParameter(fences[0], gl.SYNC_STATUS) === gl.SIGNALED) {
        gl.deleteSync(fences.shift());
      } else await yieldTask();
    }
    const before = pt.samples;
    pt.renderSample();
    if (pt.samples !== before) fences.push(gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0));
    if (!pt.isCompiling && !t.compiled) t.compiled = now();
    const samples = pt.samples;
    if (samples >= 1 && !t.firstSample) {
      const r0 = now();
      const img = readBack();
      t.firstSample = now();
      readMs += t.firstSample - r0;
      if (samples >= config.checkpoints[0]) {
        checkpoints.push({ samples, ms: t.firstSample, rgba: img });
        next = 1;
      }
    } else if (next < config.checkpoints.length && samples >= config.checkpoints[next]) {
      const r0 = now();
      const img = readBack();
      const r1 = now();
      readMs += r1 - r0;
      // The read waits for the queued samples to finish: r1 is when they had.
      checkpoints.push({ samples, ms: r1, rgba: img });
      next++;
      if (relMseBottomUp(img, ref, width, height) <= config.stopRelMse) break;
    }
    if (next >= config.checkpoints.length) break;
    if (now() > config.capMs) {
      const r0 = now();
      const img = readBack();
      const r1 = now();
      checkpoints.push({ samples: pt.samples, ms: r1, rgba: img, cap: true });
      readMs += r1 - r0;
      break;
    }
    if (pt.samples === before) await yieldTask();
  }
  for (const f of fences) gl.deleteSync(f);
  console.warn = origWarn;
  const errors = [];
  for (let e = gl.getError(); e !== gl.NO_ERROR; e = gl.getError()) errors.push(e);
  window.__peerImages = checkpoints.map((c) => c.rgba);
  return {
    info,
    timeline: t,
    readMs,
    warnings,
    glErrors: errors,
    size: [pt.target.width, pt.target.height],
    scene: summary,
    checkpoints: checkpoints.map(({ samples, ms, cap }) => ({ samples, ms, cap: !!cap })),
  };
};

/** One checkpoint image as a plain array (RGBA float, rows bottom to top). */
window.peerImage = (i) => Array.from(window.__peerImages[i]);
