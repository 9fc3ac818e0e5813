/**
 * Which display and compute paths run, and why, in plain words for the UI.
 */
import { Canvas2DDisplay } from './display-canvas2d.ts';
import { WebGLDisplay } from './display-webgl.ts';
import type { Display } from './display.ts';
import type { ComputeMode, PathTracerOptions } from './types.ts';

export function chooseCompute(options: PathTracerOptions): { compute: ComputeMode; why: string } {
  if (options.shared === 'off') {
    return { compute: 'transfer', why: 'shared memory was turned off (shared=off)' };
  }
  // Browsers hide SharedArrayBuffer on pages that are not cross-origin
  // isolated, so that is the likelier reason and is named first.
  if (typeof crossOriginIsolated !== 'undefined' && !crossOriginIsolated) {
    return {
      compute: 'transfer',
      why: 'the page is not cross-origin isolated (no COOP/COEP headers), so SharedArrayBuffer is off',
    };
  }
  if (typeof SharedArrayBuffer === 'undefined') {
    return { compute: 'transfer', why: 'this browser offers no SharedArrayBuffer' };
  }
  return { compute: 'shared', why: 'workers write one shared accumulator (cross-origin isolated)' };
}

export function createDisplay(
  canvas: HTMLCanvasElement,
  options: PathTracerOptions,
): { display: Display; why: string } {
  if (options.display === 'canvas2d') {
    return { display: new Canvas2DDisplay(canvas), why: 'Canvas 2D display was requested' };
  }
  try {
    return { display: new WebGLDisplay(canvas), why: 'WebGL2 shows the float accumulator' };
  } catch (e) {
    const reason = e instanceof Error ? e.message : String(e);
    // A canvas keeps the first context type it gave out; a failed WebGL2
    // request returned none, so a 2D context is still available.
    return {
      display: new Canvas2DDisplay(canvas),
      why: `${reason}, so Canvas 2D tone maps on the CPU`,
    };
  }
}
