/**
 * A render worker's warm-up (src/cli/warm-up.ts says why and when): two small scenes
 * built and compiled here, in the worker — one large enough for the BVH, one under
 * its threshold (the plain list), with the three kinds of material — traced a row at
 * a time into a film of its own that is thrown away, until the main thread raises the
 * stop word or the budget is spent. What V8 learns here (type feedback, optimised
 * code) is what a cold first round would otherwise spend its time on.
 */
import { Film } from '../../src/core/film/film.ts';
import { RenderStats } from '../../src/core/integrator/render-stats.ts';
import { compileScene } from '../../src/core/scene/compile/compile.ts';
import type { MaterialDesc, Scene, ShapeDesc } from '../../src/core/scene/format/types.ts';
import { createTracer, type StripeJob } from './stripes.ts';

/** Side of the throw-away film. */
const WARM_SIZE = 32;

const NONE: [number, number, number] = [0, 0, 0];
const MATERIALS: Record<string, MaterialDesc> = {
  ground: { type: 'diffuse', albedo: [0.6, 0.6, 0.6], emission: NONE },
  red: { type: 'diffuse', albedo: [0.7, 0.2, 0.15], emission: NONE },
  metal: { type: 'conductor', color: [0.9, 0.8, 0.5], roughness: 0.2, emission: NONE },
  glass: { type: 'dielectric', ior: 1.5, color: [1, 1, 1], roughness: 0, emission: NONE },
  lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [10, 10, 10] },
};

/** A field of side² spheres of every material on a ground quad under a quad lamp. */
export function warmScene(side: number): Scene {
  const kinds = ['red', 'metal', 'glass', 'ground'];
  const shapes: ShapeDesc[] = [
    {
      type: 'quad',
      corner: [-side, 0, -side],
      u: [0, 0, 2 * side],
      v: [2 * side, 0, 0],
      material: 'ground',
    },
    { type: 'quad', corner: [-1, side, -1], u: [2, 0, 0], v: [0, 0, 2], material: 'lamp' },
  ];
  for (let i = 0; i < side * side; i++) {
    const x = (i % side) - side / 2 + 0.5;
    const z = Math.floor(i / side) - side / 2 + 0.5;
    shapes.push({ type: 'sphere', center: [x, 0.3, z], radius: 0.3, material: kinds[i % 4] });
  }
  return {
    format: 'pathwise-scene/1',
    name: 'warm-up',
    camera: {
      position: [0, side * 0.6, -side * 0.6],
      target: [0, 0, 0],
      up: [0, 1, 0],
      fovY: 45,
      aperture: 0,
      focusDistance: 1,
    },
    settings: { width: WARM_SIZE, height: WARM_SIZE, maxBounces: 6, spp: 1 },
    environment: [0.05, 0.05, 0.06],
    materials: MATERIALS,
    shapes,
  };
}

/** The settings of the render to come that a warm-up can know before its scene is read. */
export type WarmJob = Pick<StripeJob, 'maxBounces' | 'seed' | 'estimator' | 'sampler'>;

/** Traces the warm-up scenes until `stop[0]` is raised or `budgetMs` is spent. */
export function warmUp(job: WarmJob, budgetMs: number, stop: Int32Array): void {
  const end = performance.now() + budgetMs;
  // 64 spheres (a BVH) and 9 (a list).
  const tracers = [warmScene(8), warmScene(3)].map((scene) =>
    createTracer(
      { ...job, camera: scene.camera, width: WARM_SIZE, height: WARM_SIZE, stripeRows: 1 },
      compileScene(scene),
    ),
  );
  const scratch = new Film(WARM_SIZE, WARM_SIZE);
  const stats = new RenderStats();
  for (let s = 0; ; s++) {
    for (let y = 0; y < WARM_SIZE; y++) {
      for (const t of tracers) {
        if (Atomics.load(stop, 0) !== 0 || performance.now() >= end) return;
        t.renderRows(scratch, y, y + 1, s, s + 1, stats);
      }
    }
  }
}
