/**
 * Portable float maps as netpbm and Paul Debevec's HDRShop define them: `PF` (colour) or
 * `Pf` (grey), then `W H`, then a scale whose sign gives the byte order (negative: little
 * endian), each line ended by one whitespace byte; then W × H texels of 32-bit floats,
 * rows from the bottom of the image up.
 */
import { ByteWriter, ascii, concat } from './bytes.ts';
import type { Rng } from './rng.ts';
import { envScene } from './scene-wrap.ts';
import type { Generator, Mutation, Sample } from './types.ts';

interface Pfm {
  colour: boolean;
  le: boolean;
  width: number;
  height: number;
  data: number[]; // channels × W × H, bottom row first
  header?: string;
}

export function encodePfm(p: Pfm): Uint8Array {
  const scale = p.le ? '-1.0' : '1.0';
  const header = ascii(p.header ?? `${p.colour ? 'PF' : 'Pf'}\n${p.width} ${p.height}\n${scale}\n`);
  const w = new ByteWriter();
  for (const v of p.data) w.f32(v, p.le);
  return concat([header, w.done()]);
}

function mutations(p: Pfm): Mutation[] {
  const f = (q: Pfm) => ({ 'sky.pfm': encodePfm(q) });
  const m = (name: string, edit: (q: Pfm, rng: Rng) => void): Mutation => ({
    name,
    apply: (rng) => {
      const q = structuredClone(p);
      edit(q, rng);
      return f(q);
    },
  });
  const tag = p.colour ? 'PF' : 'Pf';
  const s = p.le ? '-1.0' : '1.0';
  return [
    m('pfm:non-finite', (q, r) => {
      q.data[r.int(q.data.length)] = r.pick([NaN, Infinity, -Infinity]);
    }),
    m('pfm:negative', (q, r) => {
      q.data[r.int(q.data.length)] = -r.float(0.1, 10);
    }),
    m('pfm:huge-value', (q, r) => {
      q.data[r.int(q.data.length)] = r.pick([3e38, 1e13, 1e20]);
    }),
    m('pfm:subnormal', (q) => {
      q.data.fill(1e-45);
    }),
    m('pfm:size-huge', (q) => void (q.header = `${tag}\n16384 8192\n${s}\n`)),
    m('pfm:size-absurd', (q) => void (q.header = `${tag}\n4000000000 4000000000\n${s}\n`)),
    m('pfm:size-zero', (q) => void (q.header = `${tag}\n0 ${p.height}\n${s}\n`)),
    m('pfm:size-negative', (q) => void (q.header = `${tag}\n-${p.width} ${p.height}\n${s}\n`)),
    m('pfm:size-larger', (q) => void (q.header = `${tag}\n${p.width} ${p.height + 1}\n${s}\n`)),
    m('pfm:scale-zero', (q) => void (q.header = `${tag}\n${p.width} ${p.height}\n0.0\n`)),
    m(
      'pfm:scale-nan',
      (q, r) =>
        void (q.header = `${tag}\n${p.width} ${p.height}\n${r.pick(['nan', 'inf', '-inf', 'x'])}\n`),
    ),
    m(
      'pfm:wrong-magic',
      (q, r) =>
        void (q.header = `${r.pick(['P6', 'PG', 'pf', 'PF4'])}\n${p.width} ${p.height}\n${s}\n`),
    ),
    m(
      'pfm:size-garbage',
      (q, r) =>
        void (q.header = `${tag}\n${r.pick(['1e3 2', '0x10 4', '3.5 2', '+4 4', '4'])}\n${s}\n`),
    ),
    m(
      'pfm:header-comment',
      (q) => void (q.header = `${tag}\n# a comment\n${p.width} ${p.height}\n${s}\n`),
    ),
    m('pfm:crlf', (q) => void (q.header = `${tag}\r\n${p.width} ${p.height}\r\n${s}\r\n`)),
    m(
      'pfm:long-header-line',
      (q) => void (q.header = `${tag}\n${' '.repeat(100_000)}${p.width} ${p.height}\n${s}\n`),
    ),
    {
      name: 'pfm:truncated',
      apply: (rng) => {
        const b = encodePfm(p);
        return { 'sky.pfm': b.slice(0, b.length - rng.range(1, Math.min(64, b.length - 1))) };
      },
    },
    {
      name: 'pfm:trailing',
      apply: () => ({ 'sky.pfm': concat([encodePfm(p), new Uint8Array(12)]) }),
    },
  ];
}

export const pfmGenerator: Generator = {
  format: 'pfm',
  generate(rng: Rng): Sample {
    const colour = rng.chance(0.8);
    const le = rng.chance(0.5);
    const width = rng.range(1, 32);
    const height = rng.range(1, 16);
    const ch = colour ? 3 : 1;
    const data = Array.from({ length: width * height * ch }, (_, i) =>
      Math.fround(0.2 + ((i * 7919) % 97) / 50),
    );
    const p: Pfm = { colour, le, width, height, data };
    return {
      variant: `${colour ? 'colour' : 'grey'} ${le ? 'LE' : 'BE'}`,
      files: { 'sky.pfm': encodePfm(p), 'scene.json': envScene('sky.pfm') },
      target: 'sky.pfm',
      args: ['render', 'scene.json'],
      lit: true,
      mutations: mutations(p),
    };
  },
};
