/**
 * Camera controls on the canvas, for pointer, touch and keyboard alike:
 *
 * - drag (one pointer) to orbit, wheel or pinch (two touches) to dolly,
 *   click or tap without dragging to focus on the surface there;
 * - the canvas is focusable: arrow keys orbit (Shift for larger steps),
 *   + and − dolly, Enter focuses on the centre of the view.
 *
 * While the camera moves the controller renders a low-resolution preview;
 * once input has rested for REST_MS the full-resolution film takes over
 * and refines on top of the preview.
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
/** An arrow key orbits as far as a drag of this many CSS pixels (Shift: four times). */
const KEY_ORBIT_PIXELS = 12;
/** + and − move the eye by this factor toward or away from the target. */
const KEY_DOLLY = 0.9;

/** What the keys do, for labels and help texts. */
export const KEYBOARD_HELP = 'Arrow keys orbit, + and − zoom, Enter focuses on the centre';

export function attachCameraControls(target: CameraTarget, canvas: HTMLCanvasElement): () => void {
  /** Pointers down on the canvas, by id: where each is now. */
  const pointers = new Map<number, { x: number; y: number }>();
  let startX = 0;
  let startY = 0;
  let dragging = false;
  /** Distance between two touches at the last pinch step (0: no pinch). */
  let pinchDistance = 0;
  let restTimer: ReturnType<typeof setTimeout> | undefined;

  const rest = (): void => {
    clearTimeout(restTimer);
    restTimer = setTimeout(() => target.endPreview(), REST_MS);
  };

  const twoPointDistance = (): number => {
    const [a, b] = [...pointers.values()];
    return Math.hypot(a.x - b.x, a.y - b.y);
  };

  const down = (e: PointerEvent): void => {
    if (e.pointerType === 'mouse' && e.button !== 0) return;
    if (pointers.size >= 2) return;
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
    canvas.setPointerCapture?.(e.pointerId);
    if (pointers.size === 1) {
      startX = e.clientX;
      startY = e.clientY;
      dragging = false;
    } else {
      // A second finger: from now on this is a pinch, never a click.
      dragging = true;
      pinchDistance = twoPointDistance();
    }
  };

  const move = (e: PointerEvent): void => {
    const p = pointers.get(e.pointerId);
    if (!p) return;
    if (pointers.size === 2) {
      p.x = e.clientX;
      p.y = e.clientY;
      const d = twoPointDistance();
      if (pinchDistance > 0 && d > 0 && d !== pinchDistance) {
        target.beginPreview();
        // Fingers apart zoom in: the eye moves toward the target.
        target.dolly(pinchDistance / d);
        rest();
      }
      pinchDistance = d;
      return;
    }
    if (!dragging && Math.hypot(e.clientX - startX, e.clientY - startY) < CLICK_SLOP) return;
    dragging = true;
    // On every move, not only the first: after a rest (full resolution)
    // the drag goes on in the preview again.
    target.beginPreview();
    const dx = e.clientX - p.x;
    const dy = e.clientY - p.y;
    p.x = e.clientX;
    p.y = e.clientY;
    if (dx !== 0 || dy !== 0) target.orbit(dx, dy);
    rest();
  };

  const up = (e: PointerEvent): void => {
    if (!pointers.has(e.pointerId)) return;
    pointers.delete(e.pointerId);
    if (canvas.hasPointerCapture?.(e.pointerId)) canvas.releasePointerCapture(e.pointerId);
    pinchDistance = 0;
    if (pointers.size > 0) {
      // One finger of a pinch lifted: the other goes on as a drag from here.
      const [rest] = pointers.values();
      startX = rest.x;
      startY = rest.y;
      return;
    }
    if (dragging) {
      clearTimeout(restTimer);
      target.endPreview();
    } else if (e.type === 'pointerup') {
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

  const key = (e: KeyboardEvent): void => {
    if (e.altKey || e.ctrlKey || e.metaKey) return;
    const step = KEY_ORBIT_PIXELS * (e.shiftKey ? 4 : 1);
    let handled = true;
    switch (e.key) {
      case 'ArrowLeft':
        target.beginPreview();
        target.orbit(-step, 0);
        break;
      case 'ArrowRight':
        target.beginPreview();
        target.orbit(step, 0);
        break;
      case 'ArrowUp':
        target.beginPreview();
        target.orbit(0, -step);
        break;
      case 'ArrowDown':
        target.beginPreview();
        target.orbit(0, step);
        break;
      case '+':
      case '=':
        target.beginPreview();
        target.dolly(KEY_DOLLY);
        break;
      case '-':
      case '_':
        target.beginPreview();
        target.dolly(1 / KEY_DOLLY);
        break;
      case 'Enter': {
        const rect = canvas.getBoundingClientRect();
        target.focusAt(rect.width / 2, rect.height / 2);
        break;
      }
      default:
        handled = false;
    }
    if (!handled) return;
    // Arrow keys would otherwise scroll the page.
    e.preventDefault();
    if (e.key !== 'Enter') rest();
  };

  canvas.addEventListener('pointerdown', down);
  canvas.addEventListener('pointermove', move);
  canvas.addEventListener('pointerup', up);
  canvas.addEventListener('pointercancel', up);
  canvas.addEventListener('wheel', wheel, { passive: false });
  canvas.addEventListener('keydown', key);
  // Touch drags and pinches move the camera instead of scrolling or zooming the page.
  const touchAction = canvas.style.touchAction;
  canvas.style.touchAction = 'none';
  // Reachable with Tab, unless the page already placed it in the tab order.
  const addedTabIndex = !canvas.hasAttribute('tabindex');
  if (addedTabIndex) canvas.tabIndex = 0;
  const shortcuts = canvas.getAttribute('aria-keyshortcuts');
  canvas.setAttribute('aria-keyshortcuts', 'ArrowLeft ArrowRight ArrowUp ArrowDown + - Enter');
  return () => {
    clearTimeout(restTimer);
    canvas.removeEventListener('pointerdown', down);
    canvas.removeEventListener('pointermove', move);
    canvas.removeEventListener('pointerup', up);
    canvas.removeEventListener('pointercancel', up);
    canvas.removeEventListener('wheel', wheel);
    canvas.removeEventListener('keydown', key);
    canvas.style.touchAction = touchAction;
    if (addedTabIndex) canvas.removeAttribute('tabindex');
    if (shortcuts === null) canvas.removeAttribute('aria-keyshortcuts');
    else canvas.setAttribute('aria-keyshortcuts', shortcuts);
  };
}
