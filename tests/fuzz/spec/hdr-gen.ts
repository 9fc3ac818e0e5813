/**
 * Radiance RGBE pictures written from Greg Ward's description ("Real Pixels", Graphics
 * Gems II, and the Radiance file-format notes): a text header ending in an empty line, a
 * resolution line `-Y H +X W`, then scanlines of (r, g, b, e) bytes, flat or in the "new"
 * run-length encoding (each scanline `2 2 W>>8 W&255`, then the four components one
 * after the other in runs: a byte > 128 repeats the next value `byte − 128` times, a byte
 * n ≤ 128 is followed by n literal values). Widths 8 … 32767 may be run-length encoded.
 */
import { ByteWriter, ascii, concat } from './bytes.ts';
import type { Rng } from './rng.ts';
import { envScene } from './scene-wrap.ts';
import type { Generator, Mutation, Sample } from './types.ts';

export interface HdrImage {
  width: number;
  height: number;
  rgbe: Uint8Array; // 4 bytes a texel, rows top to bottom
}

/** Ward's float → RGBE: the shared exponent of the largest component. */
export function toRgbe(r: number, g: number, b: number): number[] {
  const v = Math.max(r, g, b);
  if (v < 1e-32) return [0, 0, 0, 0];
  const e = Math.floor(Math.log2(v)) + 1; // v = m · 2^e with m in [0.5, 1)
  const scale = 256 / 2 ** e;
  return [Math.floor(r * scale), Math.floor(g * scale), Math.floor(b * scale), e + 128];
}

export function randomHdr(rng: Rng, width: number, height: number): HdrImage {
  const rgbe = new Uint8Array(width * height * 4);
  const band = rng.int(3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      // Smooth bands (long runs) with a little noise (literal stretches).
      const sky = y < height / 2 ? 1 + band : 0.2;
      const n = rng.chance(0.3) ? rng.float(0, 0.3) : 0;
      rgbe.set(toRgbe(sky * 0.5 + n, sky * 0.7, sky + n), (y * width + x) * 4);
    }
  }
  return { width, height, rgbe };
}

interface HdrOptions {
  rle: boolean;
  headerLines?: string[];
  resolution?: string;
  /** Edits of the run-length stream of scanline 0, component 0. */
  badRun?: 'overflow' | 'zero' | 'short-width';
}

/** Runs of one component plane, Ward's encoder: runs of ≥ 4 equal bytes, else literals. */
function encodePlane(w: ByteWriter, plane: number[]): void {
  let i = 0;
  while (i < plane.length) {
    let run = 1;
    while (i + run < plane.length && run < 127 && plane[i + run] === plane[i]) run++;
    if (run >= 4) {
      w.u8(128 + run).u8(plane[i]);
      i += run;
      continue;
    }
    let lit = 1;
    while (i + lit < plane.length && lit < 128) {
      const j = i + lit;
      if (
        j + 3 < plane.length &&
        plane[j] === plane[j + 1] &&
        plane[j] === plane[j + 2] &&
        plane[j] === plane[j + 3]
      )
        break;
      lit++;
    }
    w.u8(lit);
    for (let k = 0; k < lit; k++) w.u8(plane[i + k]);
    i += lit;
  }
}

export function encodeHdr(img: HdrImage, o: HdrOptions): Uint8Array {
  const head = o.headerLines ?? ['#?RADIANCE', '# spec-fuzz', 'FORMAT=32-bit_rle_rgbe'];
  const header = ascii(
    `${head.join('\n')}\n\n${o.resolution ?? `-Y ${img.height} +X ${img.width}`}\n`,
  );
  const w = new ByteWriter();
  const { width, height, rgbe } = img;
  for (let y = 0; y < height; y++) {
    const row = rgbe.subarray(y * width * 4, (y + 1) * width * 4);
    if (!o.rle) {
      w.bytes(row);
      continue;
    }
    const declared = o.badRun === 'short-width' && y === 0 ? width - 1 : width;
    w.u8(2)
      .u8(2)
      .u8(declared >> 8)
      .u8(declared & 0xff);
    for (let c = 0; c < 4; c++) {
      const plane = Array.from({ length: width }, (_, x) => row[x * 4 + c]);
      if (y === 0 && c === 0 && o.badRun === 'overflow') {
        w.u8(128 + 127).u8(plane[0]); // a run of 127 in a shorter scanline
        w.u8(128 + 127).u8(plane[0]);
        continue;
      }
      if (y === 0 && c === 0 && o.badRun === 'zero') w.u8(0); // a literal of no bytes
      encodePlane(w, plane);
    }
  }
  return concat([header, w.done()]);
}

function mutations(img: HdrImage, rle: boolean): Mutation[] {
  const f = (bytes: Uint8Array) => ({ 'sky.hdr': bytes });
  const m = (name: string, o: Partial<HdrOptions>, im: HdrImage = img): Mutation => ({
    name,
    apply: () => f(encodeHdr(im, { rle, ...o })),
  });
  const { width: W, height: H } = img;
  return [
    m('hdr:size-huge', { resolution: `-Y 8192 +X 16384` }),
    m('hdr:size-absurd', { resolution: `-Y 1000000000 +X 1000000000` }),
    m('hdr:size-zero', { resolution: `-Y 0 +X ${W}` }),
    m('hdr:size-negative', { resolution: `-Y -${H} +X ${W}` }),
    m('hdr:size-taller', { resolution: `-Y ${H + 1} +X ${W}` }),
    m('hdr:size-wider', { resolution: `-Y ${H} +X ${W + 3}` }),
    m('hdr:other-orientation', { resolution: `+Y ${H} -X ${W}` }),
    m('hdr:transposed', { resolution: `+X ${W} -Y ${H}` }),
    m('hdr:resolution-garbage', { resolution: `-Y ${H}.5 +X 1e3` }),
    m('hdr:no-format-line', { headerLines: ['#?RADIANCE'] }),
    m('hdr:xyze', { headerLines: ['#?RADIANCE', 'FORMAT=32-bit_rle_xyze'] }),
    m('hdr:no-magic', { headerLines: ['FORMAT=32-bit_rle_rgbe'] }),
    m('hdr:huge-header', { headerLines: ['#?RADIANCE', `# ${'x'.repeat(300_000)}`] }),
    m('hdr:exposure', { headerLines: ['#?RADIANCE', 'EXPOSURE=1e308', 'FORMAT=32-bit_rle_rgbe'] }),
    m('hdr:rle-overflow', { rle: true, badRun: 'overflow' }),
    m('hdr:rle-zero-literal', { rle: true, badRun: 'zero' }),
    m('hdr:rle-width-mismatch', { rle: true, badRun: 'short-width' }),
    {
      name: 'hdr:exponent-255',
      apply: (rng) => {
        const im = structuredClone(img);
        for (let k = 0; k < 3; k++) im.rgbe.set([255, 255, 255, 255], rng.int(W * H) * 4);
        return f(encodeHdr(im, { rle }));
      },
    },
    {
      name: 'hdr:truncated-pixels',
      apply: (rng) => {
        const b = encodeHdr(img, { rle });
        return f(b.slice(0, b.length - rng.range(1, Math.min(b.length - 40, 200))));
      },
    },
    {
      name: 'hdr:old-rle',
      apply: () => {
        // The old encoding: (1, 1, 1, n) repeats the previous texel n times (RLE of 1991).
        const b = encodeHdr(img, { rle: false });
        const at = b.length - W * H * 4 + 4;
        b.set([1, 1, 1, 255], at);
        return f(b);
      },
    },
  ];
}

export const hdrGenerator: Generator = {
  format: 'hdr',
  generate(rng: Rng): Sample {
    const rle = rng.chance(0.5);
    const img = randomHdr(rng, rle ? rng.range(8, 40) : rng.range(1, 40), rng.range(1, 20));
    return {
      variant: rle ? 'rle' : 'flat',
      files: { 'sky.hdr': encodeHdr(img, { rle }), 'scene.json': envScene('sky.hdr') },
      target: 'sky.hdr',
      args: ['render', 'scene.json'],
      lit: true,
      mutations: mutations(img, rle),
    };
  },
};
