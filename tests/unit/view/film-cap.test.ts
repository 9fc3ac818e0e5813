/**
 * The accumulator cap (src/view/film-cap.ts) and what the films do at it,
 * in Node with a stand-in canvas: a canvas asking for too many pixels gets
 * a smaller film of the same shape and a reason; a fixed size over the cap
 * is refused with the sizes named; an allocation that throws (as
 * `new SharedArrayBuffer` does when the memory is not there) makes a
 * canvas-sized film smaller, and a fixed-size one an error.
 */
import { afterEach, describe, expect, it } from 'vitest';
import { Film } from '../../../src/core/index.ts';
import { MAX_FILM_BYTES, MAX_FILM_SIDE, maxFilmPixels } from '../../../src/view/film-cap.ts';
import { FilmMemoryError, Films } from '../../../src/view/films.ts';
import type { PathTracerOptions } from '../../../src/view/types.ts';

function canvas(cssWidth: number, cssHeight: number): HTMLCanvasElement {
  return { clientWidth: cssWidth, clientHeight: cssHeight, width: 0, height: 0 } as never;
}

function films(c: HTMLCanvasElement, options: PathTracerOptions = {}, compute = 'shared') {
  return new Films(c, { renderScale: 1, ...options }, compute as 'shared', () => 2);
}

const RealSAB = globalThis.SharedArrayBuffer;
afterEach(() => {
  globalThis.SharedArrayBuffer = RealSAB;
});

/** Makes `new SharedArrayBuffer(n)` throw, as a browser out of memory does, above `limit` bytes. */
function limitSharedMemory(limit: number): void {
  globalThis.SharedArrayBuffer = class extends RealSAB {
    constructor(n: number) {
      if (n > limit) throw new RangeError('Array buffer allocation failed');
      super(n);
    }
  } as typeof SharedArrayBuffer;
}

describe('the accumulator cap', () => {
  it('is documented in bytes and holds whole films', () => {
    expect(MAX_FILM_BYTES).toBe(256 * 1024 * 1024);
    expect(Film.byteLength(1, 1) * maxFilmPixels()).toBeLessThanOrEqual(MAX_FILM_BYTES);
    expect(Film.byteLength(1, 1) * (maxFilmPixels() + 1)).toBeGreaterThan(MAX_FILM_BYTES);
  });

  it('a huge canvas gets a film under the cap, same shape, and a reason with the scale', () => {
    const f = films(canvas(20_000, 12_000));
    const [w, h] = f.fullSize();
    expect(Film.byteLength(w, h)).toBeLessThanOrEqual(MAX_FILM_BYTES);
    expect(Math.max(w, h)).toBeLessThanOrEqual(MAX_FILM_SIDE);
    expect(Math.abs(w / h - 20_000 / 12_000)).toBeLessThan(0.01);
    // Close to the cap, not far under it.
    expect(w * h).toBeGreaterThan(0.9 * maxFilmPixels());
    expect(f.capped).not.toBeNull();
    expect(f.capped!.scale).toBeCloseTo(w / 20_000, 3);
    expect(f.capped!.reason).toMatch(/accumulator cap \(256 MiB/);
    expect(f.ensureFull(4)).toBe(true);
    expect(f.full!.width).toBe(w);
  });

  it('a long thin canvas is held to the side limit', () => {
    const f = films(canvas(100_000, 10));
    const [w, h] = f.fullSize();
    expect(w).toBeLessThanOrEqual(MAX_FILM_SIDE);
    expect(h).toBeGreaterThanOrEqual(1);
    expect(f.capped).not.toBeNull();
  });

  it('an ordinary canvas is not capped', () => {
    const f = films(canvas(800, 600));
    expect(f.fullSize()).toEqual([800, 600]);
    expect(f.capped).toBeNull();
  });

  it('a fixed size over the cap is an error naming the size and the cap, made before any film', () => {
    const f = films(canvas(300, 150), { width: 16_384, height: 16_384 });
    expect(() => f.select(4)).toThrow(FilmMemoryError);
    expect(() => f.select(4)).toThrow(/16384×16384 render needs \d+ MiB .* cap of 256 MiB/);
    expect(f.full).toBeNull();
    expect(f.preview).toBeNull();
    const wide = films(canvas(300, 150), { width: 20_000, height: 2 });
    expect(() => wide.select(4)).toThrow(/over the cap of 8192 pixels a side/);
  });

  it('a SharedArrayBuffer that cannot be allocated makes the canvas film smaller, with a reason', () => {
    limitSharedMemory(8 * 1024 * 1024);
    const f = films(canvas(2000, 1000));
    expect(f.ensureFull(4)).toBe(true);
    const { width, height } = f.full!;
    expect(Film.byteLength(width, height)).toBeLessThanOrEqual(8 * 1024 * 1024);
    expect(Math.abs(width / height - 2)).toBeLessThan(0.02);
    expect(f.capped!.reason).toMatch(/memory for a larger film could not be had/);
  });

  it('a fixed-size film whose SharedArrayBuffer cannot be allocated is an error', () => {
    limitSharedMemory(1024 * 1024);
    const f = films(canvas(300, 150), { width: 1024, height: 1024 });
    expect(() => f.ensureFull(4)).toThrow(
      /could not allocate shared memory \(SharedArrayBuffer\) for a 1024×1024 film .*Array buffer allocation failed/,
    );
    expect(f.full).toBeNull();
  });

  it('without shared memory an allocation failure is caught the same way', () => {
    const RealAB = globalThis.ArrayBuffer;
    try {
      globalThis.ArrayBuffer = class extends RealAB {
        constructor(n: number) {
          if (n > 4 * 1024 * 1024) throw new RangeError('Array buffer allocation failed');
          super(n);
        }
      } as typeof ArrayBuffer;
      const f = films(canvas(300, 150), { width: 1024, height: 1024 }, 'transfer');
      expect(() => f.ensureFull(4)).toThrow(/could not allocate memory for a 1024×1024 film/);
    } finally {
      globalThis.ArrayBuffer = RealAB;
    }
  });
});
