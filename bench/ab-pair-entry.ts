/**
 * One side of an in-process A/B (bench/ab-pair.mjs): bundled once per commit, each bundle
 * with its own copy of the core, so that one process can hold both and alternate them.
 * `prepare(scene, w, h)` loads and compiles a bench scene (a JSON file, `@million` or
 * `@bunny`, bench/mesh-scenes.ts) and returns a function rendering `spp` samples per pixel
 * that reports the CPU seconds and the sum of the radiance (equal sums: equal images).
 */
import { PathTracer, RenderStats, compileScene } from '../src/core/index.ts';
import { loadBenchScene } from './mesh-scenes.ts';

export function prepare(
  file: string,
  width: number,
  height: number,
): (spp: number) => { cpu: number; sum: number } {
  const scene = loadBenchScene(file);
  const compiled = compileScene(scene);
  const tracer = new PathTracer(compiled, {
    width,
    height,
    maxBounces: 6,
    seed: 1,
    camera: scene.camera,
  });
  return (spp) => {
    const stats = new RenderStats();
    let sum = 0;
    const c0 = process.cpuUsage();
    for (let s = 0; s < spp; s++)
      for (let y = 0; y < height; y++)
        for (let x = 0; x < width; x++) {
          tracer.trace(x, y, s, stats);
          sum += tracer.lr + tracer.lg + tracer.lb;
        }
    const c = process.cpuUsage(c0);
    return { cpu: (c.user + c.system) / 1e6, sum };
  };
}
