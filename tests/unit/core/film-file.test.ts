/**
 * The `.film` codec (pathwise-film/1): a round trip keeps every bit, and
 * every kind of bad file — truncated, lying, corrupt, NaN inside — is
 * refused with one FilmFileError sentence naming the problem.
 */
import { describe, expect, it } from 'vitest';
import {
  Film,
  FilmFileError,
  crc32,
  decodeFilmFile,
  decodeFilmHeader,
  encodeFilmFile,
  filmFileLength,
  type FilmHeader,
} from '../../../src/core/index.ts';

const W = 5;
const H = 3;
const SAMPLES = 4;

function film(): Film {
  const f = new Film(W, H);
  for (let s = 0; s < SAMPLES; s++)
    for (let y = 0; y < H; y++)
      for (let x = 0; x < W; x++)
        f.addSample(x, y, (x + 1) * 0.1 + s, y * 3.7e-5, s === 2 && x === 1 ? -0.25 : 1e4 * s);
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
    spp: 16,
    ranges: [[4, 8]],
    stats: { paths: W * H * SAMPLES, segments: 123, rejected: 0 },
    ...over,
  };
}

/** Re-stamps the checksum after a test edits the bytes on purpose. */
function reseal(bytes: Uint8Array): Uint8Array {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  view.setUint32(bytes.length - 4, crc32(bytes.subarray(0, bytes.length - 4)), true);
  return bytes;
}

/** Encodes with a header object that may break the format's rules. */
function withRawHeader(raw: unknown, f = film()): Uint8Array {
  const good = encodeFilmFile(header(), f);
  const oldLen = new DataView(good.buffer).getUint32(16, true);
  const json = new TextEncoder().encode(JSON.stringify(raw));
  const payloadAt = Math.ceil((20 + oldLen) / 8) * 8;
  const payload = good.subarray(payloadAt);
  const at = Math.ceil((20 + json.length) / 8) * 8;
  const out = new Uint8Array(at + payload.length);
  out.set(good.subarray(0, 16));
  new DataView(out.buffer).setUint32(16, json.length, true);
  out.set(json, 20);
  out.set(payload, at);
  return reseal(out);
}

function refusal(bytes: Uint8Array): string {
  try {
    decodeFilmFile(bytes);
  } catch (e) {
    expect(e).toBeInstanceOf(FilmFileError);
    const message = (e as Error).message;
    expect(message.split('\n')).toHaveLength(1);
    return message;
  }
  throw new Error('the file was accepted');
}

describe('pathwise-film/1', () => {
  it('round-trips every bit of the film and the header', () => {
    const f = film();
    const bytes = encodeFilmFile(header(), f);
    const headerBytes = new DataView(bytes.buffer).getUint32(16, true);
    expect(bytes.length).toBe(filmFileLength(headerBytes, W, H));
    const back = decodeFilmFile(bytes);
    expect(back.header).toEqual(header());
    expect(
      Buffer.from(back.film.buffer as ArrayBuffer).equals(Buffer.from(f.buffer as ArrayBuffer)),
    ).toBe(true);
    // Encoding the decoded film gives the same bytes.
    expect(Buffer.from(encodeFilmFile(back.header, back.film)).equals(Buffer.from(bytes))).toBe(
      true,
    );
    expect(bytes.subarray(0, 16).toString()).toBe(
      Array.from('pathwise-film/1\n', (c) => c.charCodeAt(0)).toString(),
    );
  });

  it('escapes non-ASCII header text and reads it back', () => {
    const h = header({ renderer: 'pathwise ünïcode ✓' });
    const bytes = encodeFilmFile(h, film());
    for (const b of bytes.subarray(20, 200)) expect(b).toBeLessThan(0x80);
    expect(decodeFilmFile(bytes).header.renderer).toBe('pathwise ünïcode ✓');
  });

  it('names a truncated file, at every length', () => {
    const bytes = encodeFilmFile(header(), film());
    for (const n of [0, 7, 16, 19, 20, 60, bytes.length - 300, bytes.length - 1]) {
      expect(refusal(bytes.subarray(0, n))).toMatch(/truncated/);
    }
  });

  it('names a file longer than its header says', () => {
    const bytes = encodeFilmFile(header(), film());
    const longer = new Uint8Array(bytes.length + 8);
    longer.set(bytes);
    expect(refusal(longer)).toMatch(/more than the \d+ that its 5×3 header describes/);
  });

  it('refuses what is not a film', () => {
    expect(refusal(new TextEncoder().encode('PF\n5 3\n-1.0\n' + ' '.repeat(100)))).toMatch(
      /pathwise-film\/1: not a .film file: it does not start with "pathwise-film\/1"/,
    );
  });

  it('refuses a corrupt payload by its checksum', () => {
    const bytes = encodeFilmFile(header(), film());
    bytes[bytes.length - 40] ^= 0x10;
    expect(refusal(bytes)).toMatch(/checksum mismatch .*corrupt/);
  });

  it('refuses a lying size before reading the pixels', () => {
    // The header claims a bigger image than the bytes hold: named as truncation.
    const big = withRawHeader({ ...header(), settings: { ...header().settings, width: 4000 } });
    expect(refusal(big)).toMatch(/truncated: \d+ bytes, but a 4000×3 film needs \d+/);
    // decodeFilmHeader decides from the first bytes and the total alone.
    expect(() => decodeFilmHeader(big.subarray(0, 1000), 1e12)).toThrow(/more than/);
    const huge = withRawHeader({
      ...header(),
      settings: { ...header().settings, width: 1e6, height: 1e6 },
    });
    expect(refusal(huge)).toMatch(/at most 16777216 pixels/);
  });

  it('refuses a header length out of range', () => {
    const bytes = encodeFilmFile(header(), film());
    new DataView(bytes.buffer).setUint32(16, 0xffffffff, true);
    expect(refusal(bytes)).toMatch(/header length 4294967295 is outside/);
  });

  it.each([
    ['not JSON', '{"format": ', /header is not valid JSON/],
    ['an array', [], /not a JSON object/],
    [
      'a missing key',
      (() => {
        const h: Record<string, unknown> = { ...header() };
        delete h.key;
        return h;
      })(),
      /key is missing/,
    ],
    ['an unknown key', { ...header(), extra: 1 }, /unknown key extra/],
    [
      'another format',
      { ...header(), format: 'pathwise-film/2' },
      /format must be "pathwise-film\/1"/,
    ],
    ['a bad hash', { ...header(), scene_sha256: 'xyz' }, /scene_sha256 must be 64 lowercase hex/],
    [
      'a bad sampler',
      { ...header(), settings: { ...header().settings, sampler: 'halton' } },
      /settings.sampler must be one of/,
    ],
    [
      'a fractional seed',
      { ...header(), settings: { ...header().settings, seed: 1.5 } },
      /settings.seed must be an integer/,
    ],
    ['other fixed-point bits', { ...header(), scale_bits: 32 }, /scale_bits must be 40/],
    [
      'a range past spp',
      { ...header(), ranges: [[4, 17]] },
      /ranges\[0\]\[1\] must be an integer in \[5, 16\]/,
    ],
    ['an empty range', { ...header(), ranges: [[4, 4]] }, /ranges\[0\]\[1\]/],
    [
      'unsorted ranges',
      {
        ...header(),
        ranges: [
          [8, 9],
          [4, 6],
        ],
      },
      /sorted, disjoint and not touching/,
    ],
    [
      'touching ranges',
      {
        ...header(),
        ranges: [
          [4, 6],
          [6, 8],
        ],
      },
      /sorted, disjoint and not touching/,
    ],
    ['NaN in the header', '{"format": NaN}', /header is not valid JSON/],
  ])('refuses a header with %s', (_what, raw, message) => {
    const bytes =
      typeof raw === 'string'
        ? (() => {
            const b = withRawHeader({});
            const json = new TextEncoder().encode(raw);
            const f = new Uint8Array(Math.ceil((20 + json.length) / 8) * 8 + 8);
            f.set(b.subarray(0, 16));
            new DataView(f.buffer).setUint32(16, json.length, true);
            f.set(json, 20);
            return f;
          })()
        : withRawHeader(raw);
    expect(refusal(bytes)).toMatch(message);
  });

  it('refuses NaN, fractions and out-of-range values inside, even with a valid checksum', () => {
    const cases: [(f: Film) => void, RegExp][] = [
      [(f) => (f.hi[5] = NaN), /pixel \(1, 0\) channel G: invalid exact sum \(NaN/],
      [(f) => (f.lo[0] = 0.5), /pixel \(0, 0\) channel R: invalid exact sum/],
      [(f) => (f.lo[4 * 7 + 3] = 2 ** 52), /pixel \(2, 1\) channel L: invalid exact sum/],
      [(f) => (f.hi[8] = 2 ** 40), /pixel \(2, 0\) channel R: invalid exact sum .* for 4 samples/],
      [(f) => (f.lo[1] = -1), /pixel \(0, 0\) channel G/],
      [(f) => (f.sums[3] = 9), /pixel \(0, 0\) has 9 samples, more than the 4 of its ranges/],
      [(f) => (f.sums[7] = 3), /stats do not add up/],
    ];
    for (const [spoil, message] of cases) {
      const f = film();
      spoil(f);
      expect(refusal(encodeFilmFile(header(), f))).toMatch(message);
    }
  });

  it('refuses stats that do not add up', () => {
    const bytes = encodeFilmFile(
      header({ stats: { paths: 61, segments: 0, rejected: 1 } }),
      film(),
    );
    expect(refusal(bytes)).toMatch(/stats do not add up: 61 paths/);
  });
});

describe('pathwise-film/2 (albedo and normal)', () => {
  function auxFilm(): Film {
    const f = new Film(W, H, undefined, 0, 0, true);
    for (let s = 0; s < SAMPLES; s++)
      for (let y = 0; y < H; y++)
        for (let x = 0; x < W; x++)
          f.addSampleAux(
            x,
            y,
            { lr: x + s, lg: y * 0.5, lb: 0.25 },
            { ar: 0.1 * x, ag: 0.3, ab: s === 1 ? 1 : 0.7, nx: -0.6, ny: 0, nz: 0.8 },
          );
    return f;
  }
  const header2 = (over: Partial<FilmHeader> = {}): FilmHeader =>
    header({ format: 'pathwise-film/2', aux: ['albedo', 'normal'], ...over });

  it('round-trips every bit, aux planes included; its length has 96 bytes a pixel more', () => {
    const f = auxFilm();
    const bytes = encodeFilmFile(header2(), f);
    const headerBytes = new DataView(bytes.buffer).getUint32(16, true);
    expect(bytes.length).toBe(filmFileLength(headerBytes, W, H, true));
    expect(filmFileLength(headerBytes, W, H, true) - filmFileLength(headerBytes, W, H)).toBe(
      96 * W * H,
    );
    expect(new TextDecoder().decode(bytes.subarray(0, 16))).toBe('pathwise-film/2\n');
    const back = decodeFilmFile(bytes);
    expect(back.header).toEqual(header2());
    expect(back.film.auxHi).toEqual(f.auxHi);
    expect(back.film.auxLo).toEqual(f.auxLo);
    expect(back.film.auxMean(0)).toEqual(f.auxMean(0));
    expect(Buffer.from(encodeFilmFile(back.header, back.film)).equals(Buffer.from(bytes))).toBe(
      true,
    );
  });

  it('a version-1 file still reads, as a film without aux planes', () => {
    const back = decodeFilmFile(encodeFilmFile(header(), film()));
    expect(back.film.auxHi).toBeNull();
    expect(back.header.format).toBe('pathwise-film/1');
    expect('aux' in back.header).toBe(false);
  });

  it('refuses a header that disagrees with its version, and a film of the other kind', () => {
    expect(() => encodeFilmFile(header(), auxFilm())).toThrow(/must be pathwise-film\/2/);
    expect(() => encodeFilmFile(header2(), film())).toThrow(/no aux planes/);
    const bytes = encodeFilmFile(header2(), auxFilm());
    // The first line says 2, the header 1 (and carries aux): refused, resealed.
    const v1Header = withRawHeader2({ ...header2(), format: 'pathwise-film/1' });
    expect(refusal(v1Header)).toMatch(/format must be "pathwise-film\/2"/);
    expect(refusal(withRawHeader2({ ...header2(), aux: ['albedo'] }))).toMatch(
      /aux must be \["albedo","normal"\]/,
    );
    const { aux: _aux, ...noAux } = header2();
    expect(refusal(withRawHeader2(noAux))).toMatch(/aux is missing/);
    // A version-1 first line on a version-2 body: its header has an unknown key.
    const relabelled = bytes.slice();
    relabelled[14] = '1'.charCodeAt(0);
    expect(refusal(reseal(relabelled))).toMatch(/unknown key aux/);
  });

  it('refuses NaN and out-of-range values in the aux planes, naming the channel', () => {
    const cases: [(f: Film) => void, RegExp][] = [
      [(f) => (f.auxHi![6 + 4] = NaN), /pixel \(1, 0\) normal channel Y: invalid exact sum/],
      [(f) => (f.auxLo![0] = 0.5), /pixel \(0, 0\) albedo channel R: invalid exact sum/],
      [(f) => (f.auxHi![2] = 2 ** 40), /albedo channel B: invalid exact sum .* for 4 samples/],
    ];
    for (const [spoil, message] of cases) {
      const f = auxFilm();
      spoil(f);
      expect(refusal(encodeFilmFile(header2(), f))).toMatch(message);
    }
  });

  it('names truncation of a version-2 file', () => {
    const bytes = encodeFilmFile(header2(), auxFilm());
    for (const n of [20, 60, bytes.length - 96 * W * H, bytes.length - 1]) {
      expect(refusal(bytes.subarray(0, n))).toMatch(/truncated/);
    }
  });
});

/** withRawHeader for a version-2 file. */
function withRawHeader2(raw: unknown): Uint8Array {
  const f = new Film(W, H, undefined, 0, 0, true);
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++)
      for (let s = 0; s < SAMPLES; s++)
        f.addSampleAux(
          x,
          y,
          { lr: 1, lg: 1, lb: 1 },
          { ar: 0.5, ag: 0.5, ab: 0.5, nx: 0, ny: 1, nz: 0 },
        );
  const good = encodeFilmFile(header({ format: 'pathwise-film/2', aux: ['albedo', 'normal'] }), f);
  const oldLen = new DataView(good.buffer).getUint32(16, true);
  const json = new TextEncoder().encode(JSON.stringify(raw));
  const payload = good.subarray(Math.ceil((20 + oldLen) / 8) * 8);
  const at = Math.ceil((20 + json.length) / 8) * 8;
  const out = new Uint8Array(at + payload.length);
  out.set(good.subarray(0, 16));
  new DataView(out.buffer).setUint32(16, json.length, true);
  out.set(json, 20);
  out.set(payload, at);
  return reseal(out);
}
