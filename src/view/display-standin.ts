/**
 * WebGL2 display that survives a lost context. The GPU only displays: the
 * samples live in the film, in CPU memory, so a lost context (a driver
 * reset, the browser reclaiming contexts) loses no sample, only the
 * picture. While the context is lost, a stand-in canvas laid exactly over
 * the WebGL canvas shows the film through the Canvas 2D display (a canvas
 * keeps the kind of context it first gave out, so the WebGL canvas itself
 * cannot switch); tracing goes on meanwhile. When the context is restored,
 * the WebGL2 display is rebuilt (shaders, textures, the whole film uploaded)
 * and the stand-in removed.
 *
 * The lost event's default is prevented: that is what tells the browser
 * the page wants the context back (WebGL 1.0 spec, section 5.15.2).
 */
import type { Backdrop } from './backdrop.ts';
import { Canvas2DDisplay } from './display-canvas2d.ts';
import type { WebGLDisplay } from './display-webgl.ts';
import type { Display, DisplayPixels } from './display.ts';
import type { DisplayMode } from './types.ts';

export type ContextEvent = 'lost' | 'restored';

export class StandInDisplay implements Display {
  private readonly gl: WebGLDisplay;
  private readonly canvas: HTMLCanvasElement;
  /** The stand-in while the context is lost. */
  private overlay: HTMLCanvasElement | null = null;
  private cpu: Canvas2DDisplay | null = null;
  /** The last clear(): replayed on the display that takes over. */
  private cleared: { width: number; height: number; backdrop: Backdrop | null } | null = null;
  /** The display that takes over draws every row on its first draw. */
  private fullDraw = false;
  private destroyed = false;
  /** Told when the context is lost or back (the controller emits `fallback` and redraws). */
  onChange: ((event: ContextEvent, reason: string) => void) | null = null;

  constructor(gl: WebGLDisplay) {
    this.gl = gl;
    this.canvas = gl.canvas;
    this.canvas.addEventListener('webglcontextlost', this.lost);
    this.canvas.addEventListener('webglcontextrestored', this.restored);
  }

  get mode(): DisplayMode {
    return this.cpu ? 'canvas2d' : 'webgl2';
  }

  /** The largest texture side the WebGL2 context takes. */
  get maxTextureSize(): number {
    return this.gl.maxTextureSize;
  }

  /** Whether the WebGL2 context is lost now (the stand-in is showing). */
  get contextLost(): boolean {
    return this.cpu !== null;
  }

  private readonly lost = (event: Event): void => {
    event.preventDefault();
    if (this.destroyed || this.cpu) return;
    const overlay = document.createElement('canvas');
    // Over the WebGL canvas, invisible to pointers and assistive technology:
    // the canvas below keeps its role, label and camera controls.
    overlay.setAttribute('aria-hidden', 'true');
    overlay.style.position = 'absolute';
    overlay.style.pointerEvents = 'none';
    overlay.style.margin = '0';
    overlay.style.border = '0';
    overlay.style.padding = '0';
    this.canvas.after(overlay);
    this.overlay = overlay;
    this.place();
    this.cpu = new Canvas2DDisplay(overlay);
    this.fullDraw = true;
    this.onChange?.(
      'lost',
      'the WebGL2 context was lost, so Canvas 2D shows the image until it is restored; no sample is lost',
    );
  };

  private readonly restored = (): void => {
    if (this.destroyed || !this.cpu) return;
    try {
      this.gl.build(this.cleared?.backdrop ?? null);
    } catch {
      // Restored without float textures or shaders: the stand-in stays.
      return;
    }
    this.cpu.destroy();
    this.cpu = null;
    this.overlay?.remove();
    this.overlay = null;
    this.fullDraw = true;
    this.onChange?.(
      'restored',
      'the WebGL2 context was restored: shaders and textures rebuilt, the whole image uploaded again',
    );
  };

  /** Lays the stand-in over the WebGL canvas's content box, at the film's resolution. */
  private place(): void {
    const overlay = this.overlay!;
    const c = this.canvas;
    const left = `${c.offsetLeft + c.clientLeft}px`;
    const top = `${c.offsetTop + c.clientTop}px`;
    const width = `${c.clientWidth}px`;
    const height = `${c.clientHeight}px`;
    if (overlay.style.left !== left) overlay.style.left = left;
    if (overlay.style.top !== top) overlay.style.top = top;
    if (overlay.style.width !== width) overlay.style.width = width;
    if (overlay.style.height !== height) overlay.style.height = height;
    if (overlay.width !== c.width) overlay.width = c.width;
    if (overlay.height !== c.height) overlay.height = c.height;
  }

  private active(): Display {
    return this.cpu ?? this.gl;
  }

  draw(
    sums: Float32Array,
    filmWidth: number,
    filmHeight: number,
    exposure: number,
    dirtyRows: readonly number[] | null,
  ): void {
    if (this.cpu) this.place();
    const display = this.active();
    let rows = dirtyRows;
    if (this.fullDraw) {
      this.fullDraw = false;
      rows = null;
      if (this.cleared)
        display.clear(this.cleared.width, this.cleared.height, this.cleared.backdrop);
    }
    display.draw(sums, filmWidth, filmHeight, exposure, rows);
  }

  clear(filmWidth: number, filmHeight: number, backdrop: Backdrop | null): void {
    this.cleared = { width: filmWidth, height: filmHeight, backdrop };
    this.active().clear(filmWidth, filmHeight, backdrop);
  }

  readPixels(): DisplayPixels {
    return this.active().readPixels();
  }

  destroy(): void {
    this.destroyed = true;
    this.canvas.removeEventListener('webglcontextlost', this.lost);
    this.canvas.removeEventListener('webglcontextrestored', this.restored);
    this.cpu?.destroy();
    this.cpu = null;
    this.overlay?.remove();
    this.overlay = null;
    this.gl.destroy();
  }
}
