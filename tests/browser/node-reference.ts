/** The Node core's render of a canonical scene, the reference the browser must equal bit for bit. */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  parseScene,
  type CameraDesc,
} from '../../src/core/index.ts';
import { root } from './harness.ts';

export function nodeRender(
  scene: string,
  width: number,
  height: number,
  seed: number,
  spp: number,
  camera?: CameraDesc,
  maxBounces?: number,
): Float32Array {
  return nodeFilm(scene, width, height, seed, spp, camera, maxBounces).mean();
}

/** The Node core's film (sums and squared luminance) of the same render. */
export function nodeFilm(
  scene: string,
  width: number,
  height: number,
  seed: number,
  spp: number,
  camera?: CameraDesc,
  maxBounces?: number,
): Film {
  const parsed = parseScene(readFileSync(join(root, 'scenes', `${scene}.json`), 'utf8'));
  const tracer = new PathTracer(compileScene(parsed), {
    width,
    height,
    maxBounces: maxBounces ?? parsed.settings.maxBounces,
    seed,
    camera: camera ?? parsed.camera,
  });
  const film = new Film(width, height);
  tracer.renderRows(film, 0, height, 0, spp, new RenderStats());
  return film;
}

/** Distance along the view axis to the surface at film point (x, y): what click-to-focus sets. */
export function nodePick(
  scene: string,
  width: number,
  height: number,
  x: number,
  y: number,
): number {
  const parsed = parseScene(readFileSync(join(root, 'scenes', `${scene}.json`), 'utf8'));
  const tracer = new PathTracer(compileScene(parsed), {
    width,
    height,
    maxBounces: 1,
    camera: parsed.camera,
  });
  return tracer.pick(x, y);
}
