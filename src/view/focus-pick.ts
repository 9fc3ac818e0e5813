/**
 * Click-to-focus: the distance to the surface under a point of the canvas,
 * picked on the page with a PathTracer of the compiled scene (PathTracer.pick),
 * kept for the full film's size and rebuilt when that, the scene or the
 * camera changes.
 */
import { PathTracer, type CameraDesc, type CompiledScene } from '../core/index.ts';

export class FocusPicker {
  private picker: PathTracer | null = null;

  /** The scene or camera changed: the next pick builds its tracer afresh. */
  invalidate(): void {
    this.picker = null;
  }

  /**
   * The distance to the surface under canvas point (x, y) in CSS pixels, as
   * the full film of `width` × `height` sees it (NaN where the ray escapes).
   */
  distance(
    canvas: HTMLCanvasElement,
    compiled: CompiledScene,
    camera: CameraDesc,
    maxBounces: number,
    width: number,
    height: number,
    x: number,
    y: number,
  ): number {
    const rect = canvas.getBoundingClientRect();
    const fx = (x / (rect.width || width)) * width;
    const fy = (y / (rect.height || height)) * height;
    if (!this.picker || this.picker.width !== width || this.picker.height !== height) {
      this.picker = new PathTracer(compiled, { width, height, maxBounces, camera });
    }
    this.picker.setCamera(camera);
    return this.picker.pick(fx, fy);
  }
}
