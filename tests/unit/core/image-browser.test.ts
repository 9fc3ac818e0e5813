/**
 * The browser's image decoder (workers/browser/gltf-browser.ts) runs the same checks as
 * Node's before createImageBitmap (a lying header or a deflate bomb never reaches the
 * platform decoder), and the platform decoder's own failures read like Node's:
 * "cannot decode PNG: …". createImageBitmap and OffscreenCanvas are stood in for here;
 * tests/browser/gltf.test.ts decodes real images in Chromium.
 */
import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { decodeImageBrowser } from '../../../workers/browser/gltf-browser.ts';
import {
  IEND,
  ihdr,
  jpegImage,
  jpegWithSize,
  pngChunk,
  pngFile,
  pngImage,
  zlib,
} from '../../fuzz/image-samples.ts';

const g = globalThis as Record<string, unknown>;
let platformDecodes = 0;

beforeEach(() => {
  platformDecodes = 0;
  g.createImageBitmap = vi.fn(async () => {
    platformDecodes++;
    throw new Error('The source image could not be decoded.');
  });
  g.OffscreenCanvas = class {};
});

afterEach(() => {
  delete g.createImageBitmap;
  delete g.OffscreenCanvas;
});

describe('decodeImageBrowser', () => {
  it('a lying JPEG and a PNG bomb fail before createImageBitmap, as in Node', async () => {
    const lying = jpegWithSize(jpegImage(16, 8), 16384, 8192);
    await expect(decodeImageBrowser(lying, 'image/jpeg')).rejects.toThrow(
      /^cannot decode JPEG: the frame header claims 16384×8192 but the file has only \d+ bytes \(at least 1572864 needed\)$/,
    );
    const bomb = pngFile(ihdr(4, 4), pngChunk('IDAT', zlib(new Uint8Array(4 << 20))), IEND);
    await expect(decodeImageBrowser(bomb, 'image/png')).rejects.toThrow(
      /^cannot decode PNG: the image data inflates past the 68 bytes its 4×4 header needs$/,
    );
    const html = Uint8Array.from('<html>', (c) => c.charCodeAt(0));
    await expect(decodeImageBrowser(html, 'image/png')).rejects.toThrow(
      /^not a PNG or JPEG image \(it starts with 3c 68 74 6d 6c 3e, "<html>"; its mimeType says image\/png\)$/,
    );
    expect(platformDecodes).toBe(0);
  });

  it("the platform decoder's failure reads like Node's", async () => {
    await expect(decodeImageBrowser(pngImage(2, 2), 'image/png')).rejects.toThrow(
      /^cannot decode PNG: the browser could not decode it \(The source image could not be decoded\.\)$/,
    );
    expect(platformDecodes).toBe(1);
  });
});
