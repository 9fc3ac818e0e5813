/**
 * What assistive technology learns of a <pathwise-view>: the host is an
 * image (role="img") named by the author's `alt` (or `aria-label`), else by
 * the scene's name; with `camera-controls` it becomes a group whose canvas
 * is a focusable image, described by the keys that move the camera. An
 * author's own `role` or `aria-label` on the host is never overwritten.
 */
import { KEYBOARD_HELP } from '../view/interaction.ts';

/** The name used before any scene has loaded, and for scenes without a name. */
export const DEFAULT_ALT = '3D scene';

export class ViewAccessibility {
  private readonly host: HTMLElement;
  private readonly hint: HTMLElement;
  private canvas: HTMLCanvasElement;
  private sceneName = '';
  /** Attributes this class set on the host (and may update), as opposed to the author's. */
  private readonly ownHostAttributes = new Set<string>();

  constructor(host: HTMLElement, canvas: HTMLCanvasElement, shadow: ShadowRoot) {
    this.host = host;
    this.canvas = canvas;
    this.hint = document.createElement('div');
    this.hint.id = 'keys';
    this.hint.className = 'visually-hidden';
    this.hint.textContent = `${KEYBOARD_HELP}; drag, wheel or pinch with a pointer.`;
    shadow.append(this.hint);
  }

  /** A new canvas replaced the old one (a re-connected element). */
  setCanvas(canvas: HTMLCanvasElement): void {
    this.canvas = canvas;
    this.update();
  }

  setSceneName(name: string): void {
    this.sceneName = name;
    this.update();
  }

  /** The accessible name: `alt`, else the scene's name, described as a rendering. */
  name(): string {
    const alt = this.host.getAttribute('alt')?.trim();
    if (alt) return alt;
    return `${this.sceneName || DEFAULT_ALT}, rendered by pathwise`;
  }

  /** Applies the name and roles; call after any change of `alt`, `camera-controls` or scene. */
  update(): void {
    const controls = this.host.hasAttribute('camera-controls');
    const name = this.name();
    this.setHost('role', controls ? 'group' : 'img');
    this.setHost('aria-label', name);
    this.canvas.setAttribute('role', 'img');
    this.canvas.setAttribute('aria-label', name);
    if (controls) this.canvas.setAttribute('aria-describedby', this.hint.id);
    else this.canvas.removeAttribute('aria-describedby');
  }

  /** Sets a host attribute unless the author set it. */
  private setHost(attribute: string, value: string): void {
    if (this.host.hasAttribute(attribute) && !this.ownHostAttributes.has(attribute)) return;
    this.ownHostAttributes.add(attribute);
    if (this.host.getAttribute(attribute) !== value) this.host.setAttribute(attribute, value);
  }
}
