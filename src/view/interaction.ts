/**
 * Pointer controls on the canvas: drag to orbit, wheel to dolly, click
 * (without dragging) to focus. While the pointer moves the controller
 * renders a low-resolution preview; once the pointer has rested for
 * REST_MS the full-resolution film takes over and refines.
 */
export interface CameraTarget {
  orbit(dxPixels: number, dyPixels: number): void;
  dolly(factor: number): void;
  focusAt(x: number, y: number): boolean;
  beginPreview(): void;
  endPreview(): void;
}

const REST_MS = 150;
/** A press that moves less than this many CSS pixels is a click. */
const CLICK_SLOP = 4;

export function attachCameraControls(target: CameraTarget, canvas: HTMLCanvasElement): () => void {
  let pointer: number | null = null;
  let startX = 0;
  let startY = 0;
  let lastX = 0;
  let lastY = 0;
  let dragging = false;
  let restTimer: ReturnType<typeof setTimeout> | undefined;

  const rest = (): void => {
    clearTimeout(restTimer);
    restTimer = setTimeout(() => target.endPreview(), REST_MS);
  };

  const down = (e: PointerEvent): void => {
    if (pointer !== null || e.button !== 0) return;
    pointer = e.pointerId;
    canvas.setPointerCapture(e.pointerId);
    startX = lastX = e.clientX;
    startY = lastY = e.clientY;
    dragging = false;
  };

  const move = (e: PointerEvent): void => {
    if (e.pointerId !== pointer) return;
    if (!dragging && Math.hypot(e.clientX - startX, e.clientY - startY) < CLICK_SLOP) return;
    dragging = true;
    // On every move, not only the first: after a rest (full resolution)
    // the drag goes on in the preview again.
    target.beginPreview();
    const dx = e.clientX - lastX;
    const dy = e.clientY - lastY;
    lastX = e.clientX;
    lastY = e.clientY;
    if (dx !== 0 || dy !== 0) target.orbit(dx, dy);
    rest();
  };

  const up = (e: PointerEvent): void => {
    if (e.pointerId !== pointer) return;
    pointer = null;
    if (canvas.hasPointerCapture(e.pointerId)) canvas.releasePointerCapture(e.pointerId);
    if (dragging) {
      clearTimeout(restTimer);
      target.endPreview();
    } else {
      const rect = canvas.getBoundingClientRect();
      target.focusAt(e.clientX - rect.left, e.clientY - rect.top);
    }
    dragging = false;
  };

  const wheel = (e: WheelEvent): void => {
    e.preventDefault();
    target.beginPreview();
    // Pixel-mode deltas of about 100 per notch: a notch moves ~10%.
    const delta = e.deltaMode === 1 ? e.deltaY * 33 : e.deltaY;
    target.dolly(Math.exp(delta * 0.001));
    rest();
  };

  canvas.addEventListener('pointerdown', down);
  canvas.addEventListener('pointermove', move);
  canvas.addEventListener('pointerup', up);
  canvas.addEventListener('pointercancel', up);
  canvas.addEventListener('wheel', wheel, { passive: false });
  // Touch drags orbit the scene instead of scrolling the page.
  const touchAction = canvas.style.touchAction;
  canvas.style.touchAction = 'none';
  return () => {
    clearTimeout(restTimer);
    canvas.removeEventListener('pointerdown', down);
    canvas.removeEventListener('pointermove', move);
    canvas.removeEventListener('pointerup', up);
    canvas.removeEventListener('pointercancel', up);
    canvas.removeEventListener('wheel', wheel);
    canvas.style.touchAction = touchAction;
  };
}
