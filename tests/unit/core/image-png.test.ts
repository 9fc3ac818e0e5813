/**
 * PNG bounded by the file, not by its header (issue 27, findings 1, 4 and 7): the chunk
 * rules of the PNG specification, the declared size against the bytes present and the
 * texel budget, and image data inflated under a hard limit of what IHDR needs. Every
 * hostile file is built here (tests/fuzz/image-samples.ts), none is committed.
 */
import { describe, expect, it } from 'vitest';
import { FormatError } from '../../../src/core/io/format-error.ts';
import { decodeImageJs, decodePngBytes } from '../../../src/core/texture/decode-js.ts';
import { pngDataSize } from '../../../src/core/texture/png-data.ts';
import {
  IEND,
  chunkAt,
  concatBytes,
  ihdr,
  pngChunk,
  pngFile,
  pngImage,
  pngIndexed,
  pngInterlacedGrey,
  rawRows,
  zlib,
} from '../../fuzz/image-samples.ts';

/** The FormatError('PNG') message of decoding `bytes` (fails the test if it decodes). */
function pngError(bytes: Uint8Array, maxTexels?: number): string {
  try {
    decodePngBytes(bytes, maxTexels);
  } catch (e) {
    expect(e).toBeInstanceOf(FormatError);
    expect((e as FormatError).format).toBe('PNG');
    return (e as Error).message;
  }
  throw new Error('the PNG was accepted');
}

const RED_GREEN = [255, 0, 0, 0, 255, 0];

describe('PNG image data against what IHDR needs', () => {
  it('decodes valid files: RGBA, palette with tRNS, interlaced (Adam7 sizes per pass)', () => {
    const rgba = decodePngBytes(pngImage(3, 2, 6));
    expect([rgba.width, rgba.height, rgba.channels]).toEqual([3, 2, 4]);
    expect(rgba.data[5]).toBe((5 * 37 + 11) & 255);
    const indexed = decodePngBytes(
      pngIndexed(2, 1, RED_GREEN, (x) => x, [pngChunk('tRNS', [128])]),
    );
    expect([indexed.channels, ...indexed.data]).toEqual([4, 255, 0, 0, 128, 0, 255, 0, 255]);
    // 5 × 7 interlaced: passes 1, 2 (empty: x starts at 4 < 5, so one column), … 7.
    const inter = decodePngBytes(pngInterlacedGrey(5, 7, (x, y) => 10 * y + x));
    expect(Array.from(inter.data)).toEqual(
      Array.from({ length: 35 }, (_, i) => 10 * Math.floor(i / 5) + (i % 5)),
    );
    // 1 × 1 interlaced has only pass 1: one filter byte and one sample.
    expect(pngDataSize({ width: 1, height: 1, depth: 8, colorType: 0, interlaced: true })).toBe(2);
    expect(pngDataSize({ width: 4, height: 4, depth: 8, colorType: 6, interlaced: false })).toBe(
      68,
    );
  });

  it('a 4×4 image whose data inflates to 16 MiB (a deflate bomb) stops at the limit', () => {
    const bomb = pngFile(ihdr(4, 4), pngChunk('IDAT', zlib(new Uint8Array(16 << 20))), IEND);
    expect(bomb.length).toBeLessThan(40_000);
    expect(pngError(bomb)).toBe(
      'PNG: the image data inflates past the 68 bytes its 4×4 header needs',
    );
  });

  it('short image data (was "Unsupported filter: undefined")', () => {
    const short = pngFile(ihdr(4, 4), pngChunk('IDAT', zlib(rawRows(4, 3, 4, () => 1))), IEND);
    expect(pngError(short)).toBe(
      'PNG: the image data inflates to 51 bytes, but the 4×4 header needs 68',
    );
  });

  it('a scanline filter type past 4', () => {
    const raw = rawRows(4, 4, 4, () => 1);
    raw[17] = 7;
    expect(pngError(pngFile(ihdr(4, 4), pngChunk('IDAT', zlib(raw)), IEND))).toBe(
      'PNG: scanline filter type 7 at inflated byte 17 is not 0–4 (§7.3)',
    );
  });

  it('image data that is not zlib', () => {
    expect(pngError(pngFile(ihdr(4, 4), pngChunk('IDAT', [1, 2, 3, 4, 5, 6, 7, 8]), IEND))).toMatch(
      /^PNG: the image data is not a valid zlib stream \(/,
    );
  });
});

describe('PNG checksums and chunk names (found by the spec fuzzer)', () => {
  it('image data whose Adler-32 does not match (was "Unsupported filter: undefined")', () => {
    const data = zlib(rawRows(2, 2, 4, (i) => 10 * i));
    data[data.length - 1] ^= 0x01;
    expect(pngError(pngFile(ihdr(2, 2), pngChunk('IDAT', data), IEND))).toMatch(
      /^PNG: the image data's Adler-32 checksum is [0-9a-f]{8}, but the data gives [0-9a-f]{8} \(the file is damaged\)$/,
    );
  });

  it('an interlaced image of 4 bits per sample: a limit of the decoder, not "corrupt"', () => {
    // 8×8 at 4 bits, Adam7: each pass's rows are a filter byte and ceil(w·4/8) bytes.
    const raw: number[] = [];
    for (const [xs, ys, dx, dy] of [
      [0, 0, 8, 8],
      [4, 0, 8, 8],
      [0, 4, 4, 8],
      [2, 0, 4, 4],
      [0, 2, 2, 4],
      [1, 0, 2, 2],
      [0, 1, 1, 2],
    ]) {
      const w = Math.ceil((8 - xs) / dx);
      for (let y = ys; y < 8; y += dy) raw.push(0, ...new Array(Math.ceil((w * 4) / 8)).fill(0x5a));
    }
    const png = pngFile(ihdr(8, 8, 4, 0, 1), pngChunk('IDAT', zlib(raw)), IEND);
    expect(pngError(png)).toBe(
      'PNG: interlaced (Adam7) images of 4 bits per sample are not supported; save it non-interlaced or at 8 bits',
    );
  });

  it('a chunk type that is not four letters (was skipped as an ancillary chunk)', () => {
    const good = pngImage(2, 2);
    const bad = concatBytes(good.subarray(0, 33), pngChunk('t1ME', [0, 0]), good.subarray(33));
    expect(pngError(bad)).toMatch(
      /^PNG: chunk .* at byte 33: a chunk type must be four ASCII letters/,
    );
  });
});

describe('PNG declared size against the bytes present and the budget', () => {
  it('a header claiming 10000 × 10000 over a few bytes of IDAT', () => {
    const lying = pngFile(ihdr(10000, 10000, 8, 0), pngChunk('IDAT', zlib([0, 0, 0])), IEND);
    expect(pngError(lying)).toMatch(
      /^PNG: the header claims 10000×10000 \(100010000 bytes of image data\) but the file has only 11 bytes of IDAT \(at least 96914 needed\)$/,
    );
  });

  it('a header claiming more texels than the budget', () => {
    expect(pngError(pngImage(4, 4), 15)).toMatch(
      /^PNG: the header claims 4×4 texels, over the budget of 15 decoded texels/,
    );
  });
});

describe('PNG chunk rules (§5.6, §11.2)', () => {
  const idat = pngChunk('IDAT', zlib(rawRows(2, 1, 1, (i) => i)));

  it('colour type 3 without PLTE', () => {
    expect(pngError(pngFile(ihdr(2, 1, 8, 3), idat, IEND))).toBe(
      'PNG: colour type 3 (indexed-colour) needs a PLTE chunk before the image data, and there is none',
    );
  });

  it('PLTE after the image data', () => {
    const at = 8 + 25 + idat.length;
    expect(pngError(pngFile(ihdr(2, 1, 8, 3), idat, pngChunk('PLTE', RED_GREEN), IEND))).toBe(
      `PNG: chunk "PLTE" at byte ${at}: PLTE must come before the image data (IDAT)`,
    );
  });

  it('an empty PLTE (was "Cannot read properties of undefined (reading \'length\')")', () => {
    expect(pngError(pngFile(ihdr(2, 1, 8, 3), pngChunk('PLTE'), idat, IEND))).toBe(
      'PNG: chunk "PLTE" at byte 33: PLTE must hold 1 to 256 RGB entries (a multiple of 3 bytes), got 0 bytes',
    );
  });

  it('a PLTE one byte short', () => {
    expect(
      pngError(pngFile(ihdr(2, 1, 8, 3), pngChunk('PLTE', RED_GREEN.slice(0, 5)), idat, IEND)),
    ).toMatch(/PLTE must hold 1 to 256 RGB entries \(a multiple of 3 bytes\), got 5 bytes$/);
  });

  it('a file one byte short, and one without IEND (was "Offset is outside the bounds of the DataView")', () => {
    const png = pngImage(2, 2);
    expect(pngError(png.subarray(0, png.length - 1))).toMatch(
      /^PNG: the file ends at byte \d+ without an IEND chunk \(truncated\?\)$/,
    );
    expect(pngError(png.subarray(0, chunkAt(png, 'IEND')))).toMatch(/without an IEND chunk/);
  });

  it('a palette index past the PLTE entries', () => {
    expect(pngError(pngIndexed(2, 1, RED_GREEN, (x) => 3 * x))).toBe(
      "PNG: a pixel's palette index is past the 2 entries of PLTE",
    );
  });

  it('a damaged critical chunk (CRC), a length past the end, an unknown critical chunk', () => {
    const png = pngImage(2, 2);
    const bad = png.slice();
    bad[chunkAt(png, 'IDAT') + 9] ^= 1;
    expect(pngError(bad)).toMatch(/chunk "IDAT" at byte 33: its CRC does not match its data/);
    const long = png.slice();
    long.set([0x7f, 0, 0, 0], chunkAt(png, 'IDAT'));
    expect(pngError(long)).toMatch(
      /chunk "IDAT" at byte 33: its length 2130706432 runs past the end of the file/,
    );
    const unknown = pngFile(ihdr(2, 2), pngChunk('ABCD', [1]), png.subarray(33));
    expect(pngError(unknown)).toBe('PNG: chunk "ABCD" at byte 33: an unknown critical chunk');
    // Ancillary chunks, known or not, are skipped whatever their CRC.
    const ancillary = pngFile(ihdr(2, 2), pngChunk('abCD', [1], 0), png.subarray(33));
    expect(decodePngBytes(ancillary).width).toBe(2);
  });

  it('IHDR not first, a bit depth its colour type forbids, IDAT not consecutive', () => {
    const png = pngImage(2, 2);
    expect(pngError(pngFile(pngChunk('tEXt', [65, 0, 66]), png.subarray(8)))).toBe(
      'PNG: chunk "tEXt" at byte 8: the first chunk must be IHDR',
    );
    expect(pngError(pngFile(ihdr(2, 2, 4, 6), png.subarray(33)))).toMatch(
      /bit depth 4 is not allowed for colour type 6 \(truecolour with alpha; allowed: 8, 16\)$/,
    );
    const data = zlib(rawRows(2, 2, 4, () => 0));
    const split = pngFile(
      ihdr(2, 2),
      pngChunk('IDAT', data.subarray(0, 4)),
      pngChunk('tEXt', [65, 0, 66]),
      pngChunk('IDAT', data.subarray(4)),
      IEND,
    );
    expect(pngError(split)).toMatch(/IDAT chunks must be consecutive/);
    // Consecutive IDAT chunks are one stream.
    const two = pngFile(
      ihdr(2, 2),
      pngChunk('IDAT', data.subarray(0, 4)),
      pngChunk('IDAT', data.subarray(4)),
      IEND,
    );
    expect(decodePngBytes(two).width).toBe(2);
  });
});

describe('PNG through the image decoder: one line, "cannot decode PNG: …"', () => {
  it('names the format and the fault; bytes that are not an image name their first bytes', async () => {
    const short = pngFile(ihdr(4, 4), pngChunk('IDAT', zlib([0])), IEND);
    await expect(decodeImageJs(short, 'image/png')).rejects.toThrow(
      /^cannot decode PNG: the image data inflates to 1 bytes, but the 4×4 header needs 68$/,
    );
    const html = Uint8Array.from('<html><body>', (c) => c.charCodeAt(0));
    await expect(decodeImageJs(html, 'image/png')).rejects.toThrow(
      /^not a PNG or JPEG image \(it starts with 3c 68 74 6d 6c 3e 3c 62 …, "<html><b"; its mimeType says image\/png\)$/,
    );
    const webp = concatBytes(Array.from('RIFF\0\0\0\0WEBPVP8 ', (c) => c.charCodeAt(0)));
    await expect(decodeImageJs(webp)).rejects.toThrow(/^a WebP image, not PNG or JPEG$/);
  });
});
