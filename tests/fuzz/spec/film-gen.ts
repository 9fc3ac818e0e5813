/**
 * `.film` parts written from the project's own format document, docs/film-format.md (the
 * only specification of this format: so this generator shares its authors' reading of it,
 * not their code): prologue, ASCII JSON header padded to 8, per-pixel counts, high and low
 * limbs of the exact fixed-point sums (2^-40 units), CRC-32. A valid case is two or three
 * parts of one render split at arbitrary sample indices, merged by `pathwise merge`.
 */
import { createHash } from 'node:crypto';
import { ByteWriter, ascii, crc32, type Files } from './bytes.ts';
import { mutateJson } from './mutate.ts';
import type { Rng } from './rng.ts';
import type { Generator, Mutation, Sample } from './types.ts';

const MAGIC = 'pathwise-film/1\n';
const UNIT = 2 ** 40;

interface Part {
  header: Record<string, unknown>;
  /** Header text to write instead of JSON.stringify(header). */
  headerText?: string;
  count: number[];
  hi: number[]; // 4 per pixel
  lo: number[];
  crcLie?: boolean;
}

const align8 = (n: number) => (n + 7) & ~7;

export function encodeFilm(p: Part): Uint8Array {
  const h = ascii(p.headerText ?? JSON.stringify(p.header));
  const w = new ByteWriter().text(MAGIC).u32(h.length, true).bytes(h);
  while (w.length % 8) w.u8(0);
  for (const c of p.count) w.u32(c, true);
  while (w.length % 8) w.u8(0);
  for (const v of p.hi) w.f64(v, true);
  for (const v of p.lo) w.f64(v, true);
  const body = w.done();
  const crc = crc32(body) ^ (p.crcLie ? 0x5a5a5a5a : 0);
  return new ByteWriter().bytes(body).u32(crc, true).done();
}

/** One part holding samples [a, b) of every pixel; sample values from a fixed function. */
function part(common: Record<string, unknown>, w: number, h: number, a: number, b: number): Part {
  const n = w * h;
  const count: number[] = [];
  const hi: number[] = [];
  const lo: number[] = [];
  for (let i = 0; i < n; i++) {
    const sums = [0, 0, 0, 0];
    for (let s = a; s < b; s++) {
      const rgb = [0, 1, 2].map((c) => ((i * 31 + s * 17 + c * 7) % 13) / 6);
      const lum = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
      [...rgb, lum * lum].forEach((v, c) => (sums[c] += Math.round(v * UNIT)));
    }
    count.push(b - a);
    for (const t of sums) {
      hi.push(Math.floor(t / 2 ** 52));
      lo.push(t - Math.floor(t / 2 ** 52) * 2 ** 52);
    }
  }
  return {
    // A copy of its own: structuredClone keeps shared objects shared, so a mutation of one
    // part's settings would otherwise change every part's.
    header: structuredClone({
      ...common,
      ranges: [[a, b]],
      stats: { paths: n * (b - a), segments: 3 * n * (b - a), rejected: 0 },
    }),
    count,
    hi,
    lo,
  };
}

function build(rng: Rng) {
  const width = rng.range(1, 12);
  const height = rng.range(1, 12);
  const spp = rng.range(2, 6);
  const settings = {
    width,
    height,
    maxBounces: rng.range(0, 8),
    seed: rng.int(1000),
    sampler: rng.pick(['sobol', 'independent']),
    estimator: rng.pick(['nee-mis', 'bsdf']),
  };
  const renderer = 'pathwise 0.1.0';
  const scene_sha256 = createHash('sha256')
    .update(`scene ${rng.int(1e9)}`)
    .digest('hex');
  const key = createHash('sha256')
    .update(JSON.stringify({ renderer, scene_sha256, settings }))
    .digest('hex');
  const common = {
    format: 'pathwise-film/1',
    renderer,
    scene_sha256,
    settings,
    key,
    scale_bits: 40,
    spp,
  };
  const cuts = [
    0,
    ...new Set(Array.from({ length: rng.range(0, 2) }, () => rng.range(1, spp - 1))),
  ].sort((x, y) => x - y);
  cuts.push(spp);
  const parts = cuts.slice(0, -1).map((a, i) => part(common, width, height, a, cuts[i + 1]));
  return { parts };
}

const names = (n: number) => Array.from({ length: n }, (_, i) => `p${i}.film`);
const filesOf = (parts: Part[]): Files =>
  Object.fromEntries(parts.map((p, i) => [`p${i}.film`, encodeFilm(p)]));

function mutations(parts: Part[]): Mutation[] {
  const many = parts.length > 1;
  const m = (
    name: string,
    f: (ps: Part[], rng: Rng) => void | Files,
    o: { invalid?: boolean; expect?: RegExp; args?: string[] } = {},
  ): Mutation => ({
    name: `film:${name}`,
    ...o,
    apply: (rng) => {
      const ps = structuredClone(parts);
      return f(ps, rng) ?? filesOf(ps);
    },
  });
  const pick = (ps: Part[], rng: Rng) => ps[rng.int(ps.length)];
  return [
    m('header-json-random', (ps, r) => {
      const p = pick(ps, r);
      p.header = mutateJson(p.header, r).json as Record<string, unknown>;
    }),
    m(
      'header-key-twice',
      (ps, r) => {
        const p = pick(ps, r);
        p.headerText = JSON.stringify(p.header).replace('"spp":', `"spp":${p.header.spp},"spp":`);
      },
      { invalid: true },
    ),
    m(
      'header-not-json',
      (ps, r) => void (pick(ps, r).headerText = '{"format": "pathwise-film/1",'),
    ),
    m('header-not-ascii', (ps, r) => {
      const p = pick(ps, r);
      p.headerText = JSON.stringify(p.header).replace('pathwise 0.1.0', 'pathwise 0.1.0\u00e9');
    }),
    m(
      'pixels-flipped-stale-crc',
      (ps, r) => {
        const p = pick(ps, r);
        const b = encodeFilm(p);
        for (let k = 0; k < 3; k++)
          b[r.range(b.length - 64 * p.count.length - 4, b.length - 5)] ^= 1 << r.int(8);
        return { ...filesOf(ps), [`p${ps.indexOf(p)}.film`]: b };
      },
      { expect: /checksum|crc|damaged|corrupt/i },
    ),
    m(
      'header-flipped-stale-crc',
      (ps, r) => {
        const p = pick(ps, r);
        const b = encodeFilm(p);
        const at = b.indexOf(0x36, 100); // a '6' in a hash, most likely
        b[at > 0 ? at : 40] = 0x37;
        return { ...filesOf(ps), [`p${ps.indexOf(p)}.film`]: b };
      },
      { expect: /checksum|crc|damaged|corrupt/i },
    ),
    m('crc-wrong', (ps, r) => void (pick(ps, r).crcLie = true), {
      invalid: true,
      expect: /checksum|crc|damaged|corrupt/i,
    }),
    m(
      'size-lie',
      (ps, r) => {
        const p = pick(ps, r);
        (p.header.settings as { width: number }).width = r.pick([
          4096,
          1 << 20,
          (p.header.settings as { width: number }).width + 1,
        ]);
      },
      { invalid: true },
    ),
    m(
      'truncated',
      (ps, r) => {
        const k = r.int(ps.length);
        const b = encodeFilm(ps[k]);
        return { ...filesOf(ps), [`p${k}.film`]: b.subarray(0, r.int(b.length)) };
      },
      { invalid: true },
    ),
    m(
      'header-length-huge',
      (ps, r) => {
        const k = r.int(ps.length);
        const b = encodeFilm(ps[k]);
        new DataView(b.buffer).setUint32(16, r.pick([0, 0xffffffff, 1048577, 1048576]), true);
        return { ...filesOf(ps), [`p${k}.film`]: b };
      },
      { invalid: true },
    ),
    m(
      'nan-in-sums',
      (ps, r) => {
        const p = pick(ps, r);
        p.lo[r.int(p.lo.length)] = r.pick([NaN, Infinity, 0.5, 2 ** 52, -1]);
      },
      { invalid: true },
    ),
    m(
      'hi-beyond-count',
      (ps, r) => {
        const p = pick(ps, r);
        p.hi[r.int(p.hi.length)] = 2 ** 40;
      },
      { invalid: true },
    ),
    m(
      'count-above-ranges',
      (ps, r) => {
        const p = pick(ps, r);
        p.count[r.int(p.count.length)] += 1;
      },
      { invalid: true },
    ),
    m(
      'stats-do-not-add-up',
      (ps, r) => {
        const st = pick(ps, r).header.stats as { paths: number };
        st.paths += 1;
      },
      { invalid: true },
    ),
    // Pixels hold samples that no range accounts for: that, not "missing samples" (item 5).
    m('ranges-empty', (ps, r) => void (pick(ps, r).header.ranges = []), {
      invalid: true,
      expect: /count|empty/,
    }),
    m('ranges-past-spp', (ps, r) => void (pick(ps, r).header.ranges = [[0, 1e6]]), {
      invalid: true,
    }),
    m(
      'ranges-unsorted',
      (ps, r) =>
        void (pick(ps, r).header.ranges = [
          [1, 2],
          [0, 1],
        ]),
      { invalid: true },
    ),
    m('renderer-differs', (ps) => void (ps[0].header.renderer = 'pathwise 9.9.9'), {
      invalid: many,
    }),
    m('key-differs', (ps) => void (ps[0].header.key = 'f'.repeat(64)), { invalid: many }),
    m(
      'seed-differs',
      (ps) => {
        (ps[0].header.settings as { seed: number }).seed += 1;
      },
      { invalid: many },
    ),
    m('same-part-twice', (ps) => ({ ...filesOf(ps), [`p${ps.length}.film`]: encodeFilm(ps[0]) }), {
      invalid: true,
      args: ['merge', ...names(parts.length + 1)],
    }),
    m('part-missing', (ps) => filesOf(ps.slice(1)), {
      invalid: many,
      args: ['merge', ...names(Math.max(1, parts.length - 1))],
    }),
    m('not-a-film', () => ({ 'p0.film': ascii('{"format":"pathwise-scene/1"}') }), {
      invalid: true,
    }),
  ];
}

export const filmGenerator: Generator = {
  format: 'film',
  generate(rng: Rng): Sample {
    const { parts } = build(rng);
    return {
      variant: `${parts.length} part${parts.length > 1 ? 's' : ''}`,
      files: filesOf(parts),
      target: 'p0.film',
      args: ['merge', ...names(parts.length)],
      lit: false,
      mutations: mutations(parts),
    };
  },
};
