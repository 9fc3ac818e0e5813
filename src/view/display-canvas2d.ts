/**
 * Canvas 2D display: the fallback for a weak or missing GPU. The core's
 * tonemapSums runs on the main thread into an ImageData, so the picture
 * equals the WebGL2 one within 1/255 per channel.
 */
import { tonemapOverBackdrop, type Backdrop } from './backdrop.ts';
import type { Display, DisplayPixels } from './display.ts';

export class Canvas2DDisplay implements Display {
  readonly mode = 'canvas2d' as const;
  private readonly canvas: HTMLCanvasElement;
  private readonly ctx: CanvasRenderingContext2D;
  private image: ImageData | null = null;
  /** Holds a preview film's pixels before they are scaled onto the canvas. */
  private scratch: HTMLCanvasElement | null = null;
  private lastExposure = NaN;
  private backdrop: Backdrop | null = null;

  constructor(canvas: HTMLCanvasElement) {
    const ctx = canvas.getContext('2d', { alpha: false });
    if (!ctx) throw new Error('Canvas 2D is unavailable');
    this.canvas = canvas;
    this.ctx = ctx;
  }

  draw(
    sums: Float32Array,
    filmWidth: number,
    filmHeight: number,
    exposure: number,
    dirtyRows: readonly number[] | null,
  ): void {
    let rows = dirtyRows;
    if (!this.image || this.image.width !== filmWidth || this.image.height !== filmHeight) {
      this.image = new ImageData(filmWidth, filmHeight);
      rows = null;
    }
    // A new exposure changes every pixel; otherwise only changed rows are
    // tone mapped, which is what makes the CPU path affordable per frame.
    if (exposure !== this.lastExposure) rows = null;
    this.lastExposure = exposure;
    if (rows === null) rows = [0, filmHeight];
    const image = this.image;
    for (let i = 0; i < rows.length; i += 2) {
      const { data } = image;
      tonemapOverBackdrop(
        sums,
        filmWidth,
        filmHeight,
        rows[i],
        rows[i + 1],
        this.backdrop,
        exposure,
        data,
      );
    }
    const { width, height } = this.canvas;
    if (filmWidth === width && filmHeight === height) {
      for (let i = 0; i < rows.length; i += 2) {
        this.ctx.putImageData(image, 0, 0, 0, rows[i], filmWidth, rows[i + 1] - rows[i]);
      }
      return;
    }
    this.scratch ??= document.createElement('canvas');
    this.scratch.width = filmWidth;
    this.scratch.height = filmHeight;
    this.scratch.getContext('2d')!.putImageData(this.image, 0, 0);
    // Nearest neighbours, as the WebGL2 path samples the preview.
    this.ctx.imageSmoothingEnabled = false;
    this.ctx.drawImage(this.scratch, 0, 0, width, height);
  }

  clear(filmWidth: number, filmHeight: number, backdrop: Backdrop | null): void {
    this.backdrop = backdrop;
    // The next draw tone maps every row: the film's zeros show the backdrop.
    this.image = null;
  }

  readPixels(): DisplayPixels {
    const { width, height } = this.canvas;
    const data = this.ctx.getImageData(0, 0, width, height).data;
    return { width, height, rgba: new Uint8Array(data.buffer, data.byteOffset, data.byteLength) };
  }

  destroy(): void {
    this.image = null;
    this.scratch = null;
    this.backdrop = null;
  }
}
