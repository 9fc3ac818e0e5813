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
): Float32Array {
  const parsed = parseScene(readFileSync(join(root, 'scenes', `${scene}.json`), 'utf8'));
  const tracer = new PathTracer(compileScene(parsed), {
    width,
    height,
    maxBounces: parsed.settings.maxBounces,
    seed,
    camera: camera ?? parsed.camera,
  });
  const film = new Film(width, height);
  tracer.renderRows(film, 0, height, 0, spp, new RenderStats());
  return film.mean();
}
