/**
 * Which display and compute paths run, and why, in plain words for the UI.
 */
import { Canvas2DDisplay } from './display-canvas2d.ts';
import { StandInDisplay } from './display-standin.ts';
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
  if (options.display !== 'webgl2') {
    const software = softwareRenderer();
    if (software) {
      return {
        display: new Canvas2DDisplay(canvas),
        why: `WebGL2 runs in software here (${software}), which would take CPU time from the tracer, so Canvas 2D tone maps only the rows that changed`,
      };
    }
  }
  try {
    return {
      // Survives a lost context: Canvas 2D stands in until it is restored.
      display: new StandInDisplay(new WebGLDisplay(canvas)),
      why: 'WebGL2 shows the float accumulator',
    };
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

/**
 * The name of a software WebGL2 implementation (SwiftShader, llvmpipe), or
 * null for a GPU. Without a GPU every WebGL2 frame is shaded and composited
 * on the same cores the workers trace on: measured here (two cores,
 * 1280×520) that halved the rays per second, while Canvas 2D, tone mapping
 * only the rows that changed, cost next to nothing. Probed on a scratch
 * canvas, because a canvas keeps the first kind of context it gives out.
 */
function softwareRenderer(): string | null {
  const probe = document.createElement('canvas');
  const gl = probe.getContext('webgl2');
  if (!gl) return null;
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER) ?? '');
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  const match = /swiftshader|llvmpipe|softpipe|software/i.exec(name);
  return match ? match[0] : null;
}
