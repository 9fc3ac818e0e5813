/**
 * JPEG bounded by the file, not by its frame header (issue 27, findings 1 and 4): the
 * declared size against the least entropy-coded data it needs (ITU-T T.81), the texel
 * budget, and malformed segments named instead of jpeg-js's internal TypeErrors.
 */
import { describe, expect, it } from 'vitest';
import { FormatError } from '../../../src/core/io/format-error.ts';
import { decodeImageJs, decodeJpegBytes } from '../../../src/core/texture/decode-js.ts';
import { jpegMinimumBytes } from '../../../src/core/texture/jpeg-check.ts';
import { concatBytes, jpegImage, jpegWithSize, markerAt } from '../../fuzz/image-samples.ts';

function jpegError(bytes: Uint8Array, maxTexels?: number): string {
  try {
    decodeJpegBytes(bytes, maxTexels);
  } catch (e) {
    expect(e).toBeInstanceOf(FormatError);
    expect((e as FormatError).format).toBe('JPEG');
    return (e as Error).message;
  }
  throw new Error('the JPEG was accepted');
}

const sample = jpegImage(16, 8);

describe('JPEG frame size against the bytes present', () => {
  it('decodes the valid sample', () => {
    const img = decodeJpegBytes(sample);
    expect([img.width, img.height, img.channels]).toEqual([16, 8, 3]);
  });

  it('least bytes: 2 bits a block sequential, 1 progressive, blocks per component (A.1.1)', () => {
    expect(jpegMinimumBytes(16384, 8192, [[1, 1]], false)).toBe((2048 * 1024 * 2) / 8);
    expect(jpegMinimumBytes(16384, 8192, [[1, 1]], true)).toBe((2048 * 1024) / 8);
    // 4:2:0, 16 × 16: luma 2 × 2 blocks, each chroma 8 × 8 samples, one block.
    expect(
      jpegMinimumBytes(
        16,
        16,
        [
          [2, 2],
          [1, 1],
          [1, 1],
        ],
        false,
      ),
    ).toBe(2);
    // 17 × 9, 4:2:0: luma 3 × 2 blocks, chroma 9 × 5 samples, 2 × 1 blocks each.
    expect(
      jpegMinimumBytes(
        17,
        9,
        [
          [2, 2],
          [1, 1],
          [1, 1],
        ],
        false,
      ),
    ).toBe(3);
  });

  it('16384 × 8192 in a file of a few hundred bytes fails at once', () => {
    const lying = jpegWithSize(sample, 16384, 8192);
    expect(lying.length).toBeLessThan(1000);
    expect(jpegError(lying)).toBe(
      `JPEG: the frame header claims 16384×8192 but the file has only ${lying.length} bytes ` +
        '(at least 1572864 needed)',
    );
  });

  it('9000 × 9000, through the image decoder: "cannot decode JPEG: …"', async () => {
    const lying = jpegWithSize(sample, 9000, 9000);
    await expect(decodeImageJs(lying, 'image/jpeg')).rejects.toThrow(
      new RegExp(
        `^cannot decode JPEG: the frame header claims 9000×9000 but the file has only ` +
          `${lying.length} bytes \\(at least 949219 needed\\)$`,
      ),
    );
  });

  it('COM padding does not stand in for image data: the scans alone are counted', () => {
    const lying = jpegWithSize(sample, 256, 256);
    const com = concatBytes([0xff, 0xfe, 0x07, 0xd2], new Uint8Array(2000).fill(0x41));
    const padded = concatBytes(lying.subarray(0, 2), com, lying.subarray(2));
    expect(padded.length).toBeGreaterThan(768);
    expect(jpegError(padded)).toMatch(
      /^JPEG: the frame header claims 256×256 but its scans hold only \d+ bytes of entropy-coded data \(at least 768 needed\)$/,
    );
  });

  it('more texels than the budget', () => {
    expect(jpegError(sample, 100)).toBe(
      'JPEG: the frame header claims 16×8, over the budget of 100 decoded texels',
    );
  });
});

describe('JPEG segments named, not jpeg-js internals', () => {
  it('a scan naming a component the frame lacks (was "Cannot set properties of undefined (setting \'huffmanTableDC\')")', () => {
    const bad = sample.slice();
    const sos = markerAt(bad, 0xda);
    bad[sos + 5] = 9;
    expect(jpegError(bad)).toBe(
      `JPEG: the FFDA segment at byte ${sos}: the scan names component 9, which the frame lacks`,
    );
  });

  it('a scan using a Huffman table that is not defined', () => {
    const bad = sample.slice();
    const sos = markerAt(bad, 0xda);
    bad[sos + 6] = 0x30;
    expect(jpegError(bad)).toMatch(/the scan uses DC Huffman table 3, which is not defined$/);
  });

  it('a frame whose quantization table no DQT defines', () => {
    const bad = sample.slice();
    bad[markerAt(bad, 0xdb) + 1] = 0xe5; // the DQT segment becomes an APP5 segment
    expect(jpegError(bad)).toBe(
      'JPEG: component 0 uses quantization table 0, which no DQT segment defines',
    );
  });

  it('a scan before the frame header, a segment past the end, an unsupported process', () => {
    const sos = markerAt(sample, 0xda);
    const len = (sample[sos + 2] << 8) | sample[sos + 3];
    const early = concatBytes([0xff, 0xd8], sample.subarray(sos, sos + 2 + len), [0xff, 0xd9]);
    expect(jpegError(early)).toBe(
      'JPEG: the FFDA segment at byte 2: a scan before the frame header',
    );
    const long = sample.slice();
    const dht = markerAt(long, 0xc4);
    long.set([0xff, 0xff], dht + 2);
    expect(jpegError(long)).toBe(
      `JPEG: the FFC4 segment at byte ${dht} has length 65535, past the end of the file (${long.length} bytes)`,
    );
    const lossless = sample.slice();
    const sof = markerAt(lossless, 0xc0);
    lossless[sof + 1] = 0xc3;
    expect(jpegError(lossless)).toBe(
      `JPEG: the FFC3 segment at byte ${sof}: lossless JPEG is not supported`,
    );
  });

  it('every truncation and every flipped byte: a JPEG message, never a JavaScript one', () => {
    const internal = /Cannot (read|set) properties|undefined|is not a function|DataView|\[object/;
    const variants: Uint8Array[] = [];
    for (let n = 0; n < sample.length; n += 7) variants.push(sample.subarray(0, n));
    for (let i = 2; i < sample.length; i += 5) {
      const v = sample.slice();
      v[i] ^= 0xa5;
      variants.push(v);
    }
    for (const v of variants) {
      try {
        decodeJpegBytes(v);
      } catch (e) {
        expect(e).toBeInstanceOf(FormatError);
        expect((e as Error).message).not.toMatch(internal);
      }
    }
  });
});
