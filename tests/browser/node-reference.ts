/**
 * The Node core's render of a canonical scene, of a loaded scene or of a bare glTF
 * model: the reference the browser must equal bit for bit.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { nodeGltfDecoders, nodeTangentGenerator } from '../../src/cli/gltf-node.ts';
import { nodeSceneFiles } from '../../src/cli/scene-files.ts';
import { renderAdaptiveFilm } from '../helpers/render.ts';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  loadBareModel,
  parseScene,
  type CameraDesc,
  type Scene,
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
  adaptive = false,
): Float32Array {
  return nodeFilm(scene, width, height, seed, spp, camera, maxBounces, adaptive).mean();
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
  adaptive = false,
): Film {
  const parsed = parseScene(readFileSync(join(root, 'scenes', `${scene}.json`), 'utf8'));
  return sceneFilm(parsed, width, height, seed, spp, camera, maxBounces, adaptive);
}

/**
 * `adaptive`: as `pathwise render --adaptive on` does (core/film/adaptive.ts), the
 * uniform pilot, the map from it, then the passes after it at the map's rates.
 */
function sceneFilm(
  scene: Scene,
  width: number,
  height: number,
  seed: number,
  spp: number,
  camera?: CameraDesc,
  maxBounces?: number,
  adaptive = false,
): Film {
  const tracer = new PathTracer(compileScene(scene), {
    width,
    height,
    maxBounces: maxBounces ?? scene.settings.maxBounces,
    seed,
    camera: camera ?? scene.camera,
  });
  const film = new Film(width, height);
  if (adaptive) return renderAdaptiveFilm(tracer, film, spp);
  tracer.renderRows(film, 0, height, 0, spp, new RenderStats());
  return film;
}

/** The Node core's render of a loaded scene (a scene file with its meshes and maps). */
export function nodeSceneRender(
  scene: Scene,
  width: number,
  height: number,
  seed: number,
  spp: number,
): Float32Array {
  return sceneFilm(scene, width, height, seed, spp).mean();
}

/**
 * The Node core's render of the bare model `file` (its bytes) in `dir`, loaded as the
 * CLI loads it: the Node decoders (meshopt, Draco, WebP, KTX2) and MikkTSpace tangents.
 */
export async function nodeModelRender(
  bytes: Uint8Array,
  file: string,
  dir: string,
  width: number,
  height: number,
  seed: number,
  spp: number,
): Promise<Float32Array> {
  const scene = await loadBareModel(bytes, file, nodeSceneFiles(dir), {
    generateTangents: await nodeTangentGenerator(),
    decoders: nodeGltfDecoders(),
    width,
    height,
  });
  return nodeSceneRender(scene, width, height, seed, spp);
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
