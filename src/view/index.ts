/**
 * The browser layer: createPathTracer(canvas, options) renders a scene
 * progressively into a canvas with the page's shared worker pool.
 */
import { Controller } from './controller.ts';
import type { PathTracerController, PathTracerOptions } from './types.ts';

export type * from './types.ts';
export type { DisplayPixels } from './display.ts';
export { Controller } from './controller.ts';
export { droppedSceneFiles, urlSceneFiles } from '../../workers/browser/scene-files.ts';
export { mappedSceneFiles } from './scene-files.ts';

/** Starts rendering `options.scene` (or `options.src`) into `canvas`. */
export function createPathTracer(
  canvas: HTMLCanvasElement,
  options: PathTracerOptions = {},
): Controller & PathTracerController {
  return new Controller(canvas, options);
}
