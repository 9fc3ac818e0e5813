/**
 * Damaged and inconsistent `.film` parts (issue 27, findings 5 and 7): a part whose bits
 * changed after it was written is named as damaged (its checksum) before `merge`
 * compares it with other parts; a part whose pixels hold samples its header's ranges do
 * not is named as inconsistent, not as "missing samples"; a header key given twice is
 * refused with its place.
 */
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { readFilmHeader } from '../../../src/cli/film-file.ts';
import { merge } from '../../../src/cli/merge.ts';
import {
  Film,
  crc32,
  decodeFilmFile,
  encodeFilmFile,
  type FilmHeader,
} from '../../../src/core/index.ts';

const W = 4;
const H = 2;

function film(samples: number): Film {
  const f = new Film(W, H);
  for (let s = 0; s < samples; s++)
    for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) f.addSample(x, y, 0.5, 0.25, s);
  return f;
}

function header(over: Partial<FilmHeader> = {}): FilmHeader {
  return {
    format: 'pathwise-film/1',
    renderer: 'pathwise 0.1.0',
    scene_sha256: 'a'.repeat(64),
    settings: {
      width: W,
      height: H,
      maxBounces: 6,
      seed: 1,
      sampler: 'sobol',
      estimator: 'nee-mis',
    },
    key: 'b'.repeat(64),
    scale_bits: 40,
    spp: 4,
    ranges: [[0, 2]],
    stats: { paths: W * H * 2, segments: 10, rejected: 0 },
    ...over,
  };
}

function reseal(bytes: Uint8Array): Uint8Array {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  view.setUint32(bytes.length - 4, crc32(bytes.subarray(0, bytes.length - 4)), true);
  return bytes;
}

const dir = mkdtempSync(join(tmpdir(), 'pathwise-film-damage-'));
function write(name: string, bytes: Uint8Array): string {
  const path = join(dir, name);
  writeFileSync(path, bytes);
  return path;
}

/** The one-line refusal of `pathwise merge` (in process; it throws before writing). */
async function mergeRefusal(...parts: string[]): Promise<string> {
  try {
    await merge([...parts, '--out', join(dir, 'out.pfm')]);
  } catch (e) {
    return (e as Error).message;
  }
  throw new Error('merge did not refuse');
}

describe('a damaged part is named as damaged before parts are compared', () => {
  const a = write('a.film', encodeFilmFile(header(), film(2)));
  const second = encodeFilmFile(header({ ranges: [[2, 4]] }), film(2));

  it('a flipped bit in the scene hash with a stale checksum: checksum mismatch, naming the file', async () => {
    const bytes = second.slice();
    const text = new TextDecoder().decode(bytes.subarray(20, 400));
    const at = 20 + text.indexOf('"scene_sha256":"') + 16;
    bytes[at] ^= 0x07; // 'a' (0x61) → 'f' (0x66): still 64 hex digits
    const b = write('damaged.film', bytes);
    const message = await mergeRefusal(a, b);
    expect(message).toMatch(
      /^.*damaged\.film: pathwise-film\/1: checksum mismatch \(stored [0-9a-f]{8}, computed [0-9a-f]{8}\): the file is corrupt/,
    );
    expect(message).not.toMatch(/different scenes/);
    expect(() => readFilmHeader(b)).toThrow(/damaged\.film: .*checksum mismatch/);
  });

  it('a flipped bit in the pixels is found before the headers are compared', async () => {
    const bytes = second.slice();
    bytes[bytes.length - 30] ^= 0x10;
    // And a header that differs too: the damage is what is named.
    const other = encodeFilmFile(
      header({ scene_sha256: 'c'.repeat(64), ranges: [[2, 4]] }),
      film(2),
    );
    other[other.length - 30] ^= 0x10;
    expect(await mergeRefusal(a, write('pixels.film', bytes))).toMatch(
      /pixels\.film: .*checksum mismatch/,
    );
    expect(await mergeRefusal(a, write('both.film', other))).toMatch(
      /both\.film: .*checksum mismatch/,
    );
  });

  it('a flipped bit that makes the header impossible: damaged, also in the core decoder', () => {
    const bytes = encodeFilmFile(header(), film(2));
    const text = new TextDecoder().decode(bytes.subarray(20, 400));
    // "paths":16 → "paths":96: the header contradicts itself, and the checksum is stale.
    const at = 20 + text.indexOf('"paths":16') + 8;
    bytes[at] = '9'.charCodeAt(0);
    expect(() => decodeFilmFile(bytes)).toThrow(/checksum mismatch/);
    expect(() => readFilmHeader(write('impossible.film', bytes))).toThrow(/checksum mismatch/);
    // The same header written with a fresh checksum is what it says: inconsistent.
    expect(() => decodeFilmFile(reseal(bytes.slice()))).toThrow(
      /stats do not add up: 96 paths .*\(inconsistent\)/,
    );
  });
});

describe('empty ranges with samples in the pixels: inconsistent, not missing samples', () => {
  it('with stats that count no paths: named by its first pixel', async () => {
    const bytes = encodeFilmFile(
      header({ ranges: [], stats: { paths: 0, segments: 0, rejected: 0 } }),
      film(2),
    );
    const path = write('empty.film', bytes);
    const message = await mergeRefusal(path);
    expect(message).toBe(
      `${path}: pathwise-film/1: inconsistent: pixel (0, 0) has 2 samples, but the header's ranges are empty`,
    );
    expect(() => decodeFilmFile(bytes)).toThrow(/inconsistent: pixel \(0, 0\) has 2 samples/);
  });

  it('with stats that count the paths: named by the header alone', async () => {
    const path = write('empty-stats.film', encodeFilmFile(header({ ranges: [] }), film(2)));
    expect(await mergeRefusal(path)).toMatch(
      /empty-stats\.film: pathwise-film\/1: stats do not add up: 16 paths and 0 rejected, but its ranges are empty \(inconsistent\)/,
    );
  });

  it('a part with fewer samples in a pixel than the others: inconsistent stats', async () => {
    const f = film(2);
    f.sums[3] = 1; // one pixel counts 1 sample of 2
    const path = write('short.film', encodeFilmFile(header(), f));
    expect(await mergeRefusal(path)).toMatch(/short\.film: .*stats do not add up.*15 accepted/);
  });
});

describe('a header key given twice', () => {
  it('is refused with the key and its place', () => {
    const good = encodeFilmFile(header(), film(2));
    const h = new DataView(good.buffer).getUint32(16, true);
    const text = new TextDecoder().decode(good.subarray(20, 20 + h));
    // Padded with spaces to the same length, so the layout of the file stays.
    const was = '"maxBounces":6,"seed":1,';
    const twice = text.replace(was, '"seed":2,"seed":1,'.padEnd(was.length, ' '));
    expect(twice.length).toBe(text.length);
    const bytes = good.slice();
    bytes.set(new TextEncoder().encode(twice), 20);
    reseal(bytes);
    const byte = 20 + twice.indexOf('"seed":1');
    expect(() => decodeFilmFile(bytes)).toThrow(
      `pathwise-film/1: header: key settings.seed given twice, at line 1, byte ${byte}`,
    );
    expect(() => readFilmHeader(write('twice.film', bytes))).toThrow(
      /twice\.film: pathwise-film\/1: header: key settings\.seed given twice, at line 1, byte \d+/,
    );
  });
});
