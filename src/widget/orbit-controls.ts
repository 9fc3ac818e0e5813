/**
 * Orbit-on-drag and dolly-on-wheel for <pathwise-view camera-controls>.
 * The element owns these listeners (rather than the controller's
 * `cameraControls` option) so that toggling the attribute takes effect at
 * once, without tearing down the tracer.
 */
import type { PathTracerController } from '../view/types.ts';

/** Wheel delta (pixels) that dollies by a factor of e. */
const WHEEL_PIXELS_PER_E = 500;

export class OrbitControls {
  private pointerId: number | null = null;
  private lastX = 0;
  private lastY = 0;

  private readonly onPointerDown = (e: PointerEvent) => {
    if (this.pointerId !== null || e.button !== 0) return;
    this.pointerId = e.pointerId;
    this.lastX = e.clientX;
    this.lastY = e.clientY;
    this.surface.setPointerCapture(e.pointerId);
    e.preventDefault();
  };

  private readonly onPointerMove = (e: PointerEvent) => {
    if (e.pointerId !== this.pointerId) return;
    const dx = e.clientX - this.lastX;
    const dy = e.clientY - this.lastY;
    this.lastX = e.clientX;
    this.lastY = e.clientY;
    if (dx !== 0 || dy !== 0) this.controller.orbit(dx, dy);
  };

  private readonly onPointerUp = (e: PointerEvent) => {
    if (e.pointerId !== this.pointerId) return;
    this.pointerId = null;
    if (this.surface.hasPointerCapture(e.pointerId))
      this.surface.releasePointerCapture(e.pointerId);
  };

  private readonly onWheel = (e: WheelEvent) => {
    // Only a view the user chose to control may swallow page scrolling.
    e.preventDefault();
    const pixels = e.deltaMode === WheelEvent.DOM_DELTA_LINE ? e.deltaY * 16 : e.deltaY;
    this.controller.dolly(Math.exp(pixels / WHEEL_PIXELS_PER_E));
  };

  constructor(
    private readonly surface: HTMLElement,
    private readonly controller: PathTracerController,
  ) {
    surface.addEventListener('pointerdown', this.onPointerDown);
    surface.addEventListener('pointermove', this.onPointerMove);
    surface.addEventListener('pointerup', this.onPointerUp);
    surface.addEventListener('pointercancel', this.onPointerUp);
    surface.addEventListener('wheel', this.onWheel, { passive: false });
    // Touch drags would otherwise scroll the page instead of orbiting.
    surface.style.touchAction = 'none';
  }

  dispose(): void {
    this.surface.removeEventListener('pointerdown', this.onPointerDown);
    this.surface.removeEventListener('pointermove', this.onPointerMove);
    this.surface.removeEventListener('pointerup', this.onPointerUp);
    this.surface.removeEventListener('pointercancel', this.onPointerUp);
    this.surface.removeEventListener('wheel', this.onWheel);
    this.surface.style.touchAction = '';
  }
}
