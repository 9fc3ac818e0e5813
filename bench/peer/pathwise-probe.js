// The page side of the peer benchmark for pathwise: evaluated by run.mjs in
// the demo page (scene, size and seed set by its URL). It keeps copies of the
// controller's linear mean image (the film before exposure and tone mapping)
// at sample-count checkpoints, with the page clock at each, the same
// schedule and stopping rule as gpt-page.js.
export async function pathwiseProbe(config) {
  const now = () => performance.now();
  const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
  const ref = Float32Array.from(config.reference);
  // relMSE as bench/lib.mjs defines it (top-down RGB both); only to decide
  // when to stop: run.mjs recomputes every reported value with lib.mjs.
  const relMse = (x) => {
    let s = 0;
    for (let i = 0; i < ref.length; i++) {
      const d = x[i] - ref[i];
      s += (d * d) / (ref[i] * ref[i] + 0.01);
    }
    return s / ref.length;
  };
  while (!window.__pathwise?.controller) await sleep(5);
  const c = window.__pathwise.controller;
  const images = [];
  const checkpoints = [];
  let next = 0;
  let capped = false;
  for (;;) {
    const spp = c.stats().spp;
    const due = next < config.checkpoints.length && spp >= config.checkpoints[next];
    capped = now() > config.capMs;
    if (due || capped) {
      const { width, height, rgb } = c.readLinear();
      const ms = now();
      const samples = c.stats().spp;
      images.push(Float32Array.from(rgb));
      checkpoints.push({ samples, ms, cap: capped, width, height });
      while (next < config.checkpoints.length && samples >= config.checkpoints[next]) next++;
      // Past the target, go on to minRenderMs after the first image, so the
      // rate is measured over more than the first few seconds.
      const first = c.timeline().firstImage;
      const longEnough = first > 0 && ms - first >= config.minRenderMs;
      if (capped || next >= config.checkpoints.length) break;
      if (relMse(rgb) <= config.stopRelMse && longEnough) break;
    }
    await sleep(10);
  }
  window.__peerImages = images;
  window.peerImage = (i) => Array.from(window.__peerImages[i]);
  const s = c.stats();
  return {
    timeline: { ...c.timeline() },
    workers: s.workers,
    mode: c.mode,
    checkpoints,
  };
}
