/**
 * Every decoded texture of a scene in one flat typed array, so that the
 * tracer's workers share it like the rest of the scene: the texels live in
 * a SharedArrayBuffer when the page is cross-origin isolated (or in Node),
 * else in an ArrayBuffer that can be transferred or copied to each worker.
 *
 * Texels are RGBA, 16-bit linear (see srgb.ts), row 0 the top of the image
 * (glTF's uv (0, 0) is the image's top-left corner). `info` holds, per
 * image, the texel offset, width and height.
 */

export const INFO_STRIDE = 3;
export const I_OFFSET = 0;
export const I_WIDTH = 1;
export const I_HEIGHT = 2;

/** Bytes of one stored texel (RGBA × 16 bits). */
export const TEXEL_BYTES = 8;

/** Default bound on the memory of all decoded textures of one scene. */
export const DEFAULT_TEXTURE_LIMIT_BYTES = 1024 * 1024 * 1024;
/** Largest width or height of one image, as for environment maps. */
export const MAX_IMAGE_SIDE = 16384;

export interface TextureStore {
  /** RGBA texels of every image, TEXEL_BYTES each. */
  readonly texels: Uint16Array;
  /** INFO_STRIDE integers per image: offset (in texels), width, height. */
  readonly info: Int32Array;
}

export function imageCount(store: TextureStore): number {
  return store.info.length / INFO_STRIDE;
}

export const EMPTY_TEXTURES: TextureStore = {
  texels: new Uint16Array(0),
  info: new Int32Array(0),
};

/** Human-readable byte count for messages. */
export function formatBytes(n: number): string {
  if (n >= 1024 * 1024 * 1024) return `${(n / (1024 * 1024 * 1024)).toFixed(2)} GiB`;
  if (n >= 1024 * 1024) return `${(n / (1024 * 1024)).toFixed(1)} MiB`;
  if (n >= 1024) return `${(n / 1024).toFixed(1)} KiB`;
  return `${n} bytes`;
}

/**
 * Lays out images of known sizes in one store, checking every limit before
 * any texel memory is allocated: `add` each image's size, then `allocate`.
 */
export class TextureLayout {
  private readonly sizes: number[] = [];
  private texelCount = 0;

  constructor(readonly limitBytes = DEFAULT_TEXTURE_LIMIT_BYTES) {}

  /** Adds an image; returns its index. `what` names it in errors. */
  add(width: number, height: number, what: string): number {
    if (!(Number.isInteger(width) && Number.isInteger(height) && width >= 1 && height >= 1)) {
      throw new Error(`${what}: image size ${width}×${height} is not a positive integer size`);
    }
    if (width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE) {
      throw new Error(
        `${what}: image ${width}×${height} is larger than the limit of ${MAX_IMAGE_SIDE} texels per side`,
      );
    }
    const next = this.texelCount + width * height;
    if (next * TEXEL_BYTES > this.limitBytes) {
      throw new Error(
        `${what}: decoded textures would need ${formatBytes(next * TEXEL_BYTES)}, ` +
          `over the texture memory limit of ${formatBytes(this.limitBytes)}`,
      );
    }
    this.sizes.push(width, height);
    this.texelCount = next;
    return this.sizes.length / 2 - 1;
  }

  get bytes(): number {
    return this.texelCount * TEXEL_BYTES;
  }

  /** The store, texels zeroed; shared when SharedArrayBuffer exists and `shared` is set. */
  allocate(shared: boolean): TextureStore {
    const n = this.sizes.length / 2;
    const info = new Int32Array(n * INFO_STRIDE);
    let offset = 0;
    for (let i = 0; i < n; i++) {
      const w = this.sizes[2 * i];
      const h = this.sizes[2 * i + 1];
      info[i * INFO_STRIDE + I_OFFSET] = offset;
      info[i * INFO_STRIDE + I_WIDTH] = w;
      info[i * INFO_STRIDE + I_HEIGHT] = h;
      offset += w * h;
    }
    const bytes = offset * TEXEL_BYTES;
    const buffer =
      shared && typeof SharedArrayBuffer !== 'undefined'
        ? new SharedArrayBuffer(bytes)
        : new ArrayBuffer(bytes);
    return { texels: new Uint16Array(buffer), info };
  }
}
