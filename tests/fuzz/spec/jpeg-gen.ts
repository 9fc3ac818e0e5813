/**
 * JPEG cases: a baseline file from jpeg-encode.ts (grey or three components, 4:4:4 or
 * 4:2:0 or 4:2:2, with or without restart intervals) as the base-colour texture of a glTF
 * model, and mutations of its segments from the rules of T.81: frame header lies (B.2.2),
 * tables a scan names but the file lacks (B.2.3), lengths, markers out of order, a
 * truncated or damaged scan, other processes (SOF2 progressive, SOF3 lossless, SOF9
 * arithmetic).
 */
import { buildModel } from './gltf-doc.ts';
import { modelSample, type ModelEdit } from './gltf-host.ts';
import {
  dht,
  jpegSegments,
  scanData,
  segment,
  serializeJpeg,
  sof,
  sos,
  type JpegImage,
  type Segment,
} from './jpeg-encode.ts';
import type { Rng } from './rng.ts';
import type { Generator, Sample } from './types.ts';

function randomJpeg(rng: Rng): JpegImage {
  const colour = rng.chance(0.75);
  const [h, v] = colour
    ? rng.pick([
        [1, 1],
        [2, 2],
        [2, 1],
      ])
    : [1, 1];
  const comps = colour
    ? [
        { id: 1, h, v, tq: 0, td: 0, ta: 0 },
        { id: 2, h: 1, v: 1, tq: 1, td: 1, ta: 1 },
        { id: 3, h: 1, v: 1, tq: 1, td: 1, ta: 1 },
      ]
    : [{ id: 1, h: 1, v: 1, tq: 0, td: 0, ta: 0 }];
  const seed = rng.int(256);
  return {
    width: rng.range(1, 40),
    height: rng.range(1, 40),
    comps,
    value: (c, bx, by) =>
      c === 0 ? (seed + bx * 40 + by * 25) % 256 : 100 + ((bx + by + c) % 3) * 30,
    restart: rng.chance(0.3) ? rng.range(1, 3) : 0,
  };
}

function edits(img: JpegImage, jfif: boolean): ModelEdit[] {
  const segs = jpegSegments(img, jfif);
  const scan = scanData(img);
  const e = (
    name: string,
    f: (s: Segment[], rng: Rng) => Segment[] | Uint8Array,
    invalid = false,
  ): ModelEdit => ({
    name: `jpeg:${name}`,
    invalid,
    edit: (m, rng) => {
      const out = f(
        segs.map((s) => ({ ...s })),
        rng,
      );
      m.image = {
        mime: 'image/jpeg',
        bytes: out instanceof Uint8Array ? out : serializeJpeg(out, scan),
      };
    },
  });
  const at = (s: Segment[], marker: number) => s.findIndex((x) => x.marker === marker);
  const frame = (s: Segment[], im: JpegImage, marker = 0xc0, precision = 8) => {
    s[at(s, 0xc0)] = sof(marker, im, precision);
    return s;
  };
  return [
    e('frame-huge', (s, r) =>
      frame(s, {
        ...img,
        ...r.pick([
          { width: 16384, height: 8192 },
          { width: 9000, height: 9000 },
          { width: 65535, height: 65535 },
        ]),
      }),
    ),
    e('frame-larger', (s) => frame(s, { ...img, width: img.width + 16, height: img.height + 16 })),
    e('frame-height-zero', (s) => frame(s, { ...img, height: 0 })),
    e('frame-width-zero', (s) => frame(s, { ...img, width: 0 }), true),
    e('precision-12', (s) => frame(s, img, 0xc0, 12), true),
    e(
      'sampling-zero',
      (s) => frame(s, { ...img, comps: img.comps.map((c, i) => (i === 0 ? { ...c, h: 0 } : c)) }),
      true,
    ),
    e(
      'sampling-five',
      (s) => frame(s, { ...img, comps: img.comps.map((c, i) => (i === 0 ? { ...c, v: 5 } : c)) }),
      true,
    ),
    e(
      'quant-table-missing',
      (s) => frame(s, { ...img, comps: img.comps.map((c) => ({ ...c, tq: 3 })) }),
      true,
    ),
    e('dqt-removed', (s) => s.filter((x) => x.marker !== 0xdb), true),
    e('dht-removed', (s) => s.filter((x) => x.marker !== 0xc4), true),
    e(
      'scan-names-missing-table',
      (s) => {
        s[at(s, 0xda)] = sos({ ...img, comps: img.comps.map((c) => ({ ...c, td: 3, ta: 3 })) });
        return s;
      },
      true,
    ),
    e(
      'scan-names-unknown-component',
      (s) => {
        s[at(s, 0xda)] = sos({ ...img, comps: img.comps.map((c) => ({ ...c, id: c.id + 7 })) });
        return s;
      },
      true,
    ),
    e(
      'scan-no-components',
      (s) => {
        s[at(s, 0xda)] = segment(0xda, [0, 0, 63, 0]);
        return s;
      },
      true,
    ),
    e(
      'frame-components-lie',
      (s) => {
        const f = s[at(s, 0xc0)];
        f.payload = f.payload.slice();
        f.payload[5] = f.payload[5] === 1 ? 3 : 1;
        return s;
      },
      true,
    ),
    e(
      'dht-counts-overflow',
      (s) => {
        s[at(s, 0xc4)] = dht(
          0,
          0,
          [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255],
          new Array(255).fill(1),
        );
        return s;
      },
      true,
    ),
    e(
      'dht-counts-lie',
      (s) => {
        const k = at(s, 0xc4);
        s[k] = { ...s[k], payload: s[k].payload.subarray(0, s[k].payload.length - 3) };
        return s;
      },
      true,
    ),
    e('segment-length-lie', (s, r) => {
      const k = r.int(s.length);
      s[k] = { ...s[k], length: r.pick([0, 1, 2, 0xffff, s[k].payload.length + 40]) };
      return s;
    }),
    e(
      'sof-twice',
      (s) => {
        const k = at(s, 0xc0);
        s.splice(k, 0, s[k]);
        return s;
      },
      true,
    ),
    e('eoi-before-scan', (s) => [...s.slice(0, at(s, 0xda)), segment(0xd9, [])], true),
    e('huge-frame-then-eoi', (s) => [
      ...frame(s, { ...img, width: 16384, height: 8192 }).slice(0, at(s, 0xda)),
      segment(0xd9, []),
    ]),
    e('progressive', (s) => frame(s, img, 0xc2)),
    e('lossless', (s) => frame(s, img, 0xc3)),
    e('arithmetic', (s) => frame(s, img, 0xc9)),
    e('no-eoi', (s) => serializeJpeg(s, scan, false)),
    e('scan-truncated', (s, r) => serializeJpeg(s, scan.subarray(0, r.int(scan.length)), false)),
    e('scan-garbage', (s, r) =>
      serializeJpeg(
        s,
        Uint8Array.from({ length: scan.length }, () => r.int(255)),
      ),
    ),
    e('scan-empty', (s) => serializeJpeg(s, new Uint8Array(0)), true),
    e('rst-wrong-order', (s) => {
      const b = scan.slice();
      for (let i = 0; i + 1 < b.length; i++)
        if (b[i] === 0xff && b[i + 1] >= 0xd0 && b[i + 1] <= 0xd7)
          b[i + 1] = 0xd7 - (b[i + 1] - 0xd0);
      return serializeJpeg(s, b);
    }),
    e('dri-without-rst', (s) => [
      ...s.slice(0, at(s, 0xda)),
      segment(0xdd, [0, 1]),
      ...s.slice(at(s, 0xda)),
    ]),
    e('no-sos', (s) => s.filter((x) => x.marker !== 0xda), true),
    e('no-soi', (s) => serializeJpeg(s, scan).subarray(2), true),
    e('app-huge-length', (s) => [segment(0xe1, new Uint8Array(65533)), ...s]),
    e('com-segment', (s) => [segment(0xfe, new TextEncoder().encode('spec-fuzz comment')), ...s]),
  ];
}

export const jpegGenerator: Generator = {
  format: 'jpeg',
  generate(rng: Rng): Sample {
    const img = randomJpeg(rng);
    const jfif = rng.chance(0.7);
    const bytes = serializeJpeg(jpegSegments(img, jfif), scanData(img));
    const model = buildModel(rng, { bytes, mime: 'image/jpeg' });
    const ss = img.comps.length === 1 ? 'grey' : `${img.comps[0].h}x${img.comps[0].v}`;
    return modelSample(
      rng,
      model,
      edits(img, jfif),
      `${ss}${img.restart ? ` rst${img.restart}` : ''}`,
    );
  },
};
