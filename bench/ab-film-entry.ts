/**
 * One side of an in-process A/B (bench/ab-pair.mjs) through the film's row loop
 * (PathTracer.renderRows and Film.addRadiance), where bench/ab-pair-entry.ts calls trace
 * alone: what a render's worker runs. Built with `--define:AB_AUX=false` (a plain film)
 * or `--define:AB_AUX=true` (a film with albedo and normal planes, integrator/aux.ts), so
 * one pair measures what aux costs when asked for and another that it costs nothing when
 * not; the radiance sums, hence `sum`, are equal either way.
 *   esbuild bench/ab-film-entry.ts --bundle --platform=node --format=esm \
 *     --define:AB_AUX=false --outfile=NEW.mjs
 */
import { Film, PathTracer, RenderStats, compileScene } from '../src/core/index.ts';
import { loadBenchScene } from './mesh-scenes.ts';

declare const AB_AUX: boolean;

export function prepare(
  file: string,
  width: number,
  height: number,
): (spp: number) => { cpu: number; sum: number } {
  const scene = loadBenchScene(file);
  const tracer = new PathTracer(compileScene(scene), {
    width,
    height,
    maxBounces: 6,
    seed: 1,
    camera: scene.camera,
  });
  // At a commit before aux the sixth argument is ignored: a plain film.
  const film = new Film(width, height, undefined, 0, 0, AB_AUX);
  return (spp) => {
    film.clear();
    const stats = new RenderStats();
    const c0 = process.cpuUsage();
    tracer.renderRows(film, 0, height, 0, spp, stats);
    const c = process.cpuUsage(c0);
    let sum = 0;
    for (let i = 0; i < film.sums.length; i++) sum += film.sums[i];
    return { cpu: (c.user + c.system) / 1e6, sum };
  };
}
