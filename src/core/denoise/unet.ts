/**
 * The "RT" U-Net forward pass over one tile (OIDN core/unet_filter.cpp, addUNet), in a
 * workspace allocated once per tile size and reused for every tile, so the pass itself
 * allocates nothing. Feature maps live in two scratch buffers per resolution level plus
 * the three pooled skip connections, each sized for the widest layer at its level:
 *
 *   level 0 (full)  input, enc_conv0, enc_conv1 | up, dec_conv1a, dec_conv1b, dec_conv0
 *   level 1 (½)     pool1, enc_conv2            | up, dec_conv2a, dec_conv2b
 *   level 2 (¼)     pool2, enc_conv3            | up, dec_conv3a, dec_conv3b
 *   level 3 (⅛)     pool3, enc_conv4            | up, dec_conv4a, dec_conv4b
 *   level 4 (1/16)  pool4, enc_conv5a, enc_conv5b
 */
import { conv3x3Relu } from './conv3x3.ts';
import { allocPlanes, planesBytes, type Planes } from './planes.ts';
import { maxPool2x2, upsample2x } from './pool-upsample.ts';
import type { ConvLayer, UNetWeights } from './unet-weights.ts';
import {
  allocWinogradScratch,
  winogradConv3x3Relu,
  winogradFits,
  winogradRows,
  type WinogradScratch,
} from './winograd.ts';

/** Spatial alignment of a tile: four 2× poolings. */
export const TILE_ALIGNMENT = 16;

export interface UNetWorkspace {
  readonly h: number;
  readonly w: number;
  /** The network's input (3, 6 or 9 channels); write it with `at()` before `runUNet`. */
  readonly input: Planes;
  /** Holds the 3 output channels after `runUNet`. */
  readonly output: Planes;
  readonly x: readonly (readonly [Planes, Planes])[];
  readonly pool: readonly Planes[];
  readonly winograd: WinogradScratch;
}

/** The feature maps' sizes, [channels, h, w], in allocation order (see the header). */
function workspaceMaps(weights: UNetWeights, h: number, w: number): [number, number, number][] {
  if (h % TILE_ALIGNMENT || w % TILE_ALIGNMENT || h <= 0 || w <= 0)
    throw new RangeError(`U-Net tile ${w}×${h} is not a positive multiple of ${TILE_ALIGNMENT}`);
  const L = byName(weights);
  const out = (n: string): number => L(n).outChannels;
  const width = [
    Math.max(
      out('enc_conv0'),
      out('enc_conv1'),
      out('dec_conv2b'),
      out('dec_conv1a'),
      out('dec_conv1b'),
      3,
    ),
    Math.max(out('enc_conv2'), out('dec_conv3b'), out('dec_conv2a'), out('dec_conv2b')),
    Math.max(out('enc_conv3'), out('dec_conv4b'), out('dec_conv3a'), out('dec_conv3b')),
    Math.max(out('enc_conv4'), out('enc_conv5b'), out('dec_conv4a'), out('dec_conv4b')),
    Math.max(out('enc_conv5a'), out('enc_conv5b')),
  ];
  const maps: [number, number, number][] = [];
  for (let k = 0; k < width.length; k++)
    maps.push([width[k]!, h >> k, w >> k], [width[k]!, h >> k, w >> k]);
  for (const [k, n] of [
    [1, 'enc_conv1'],
    [2, 'enc_conv2'],
    [3, 'enc_conv3'],
    [4, 'enc_conv4'],
  ] as const)
    maps.push([out(n), h >> k, w >> k]);
  maps.push([weights.inputChannels, h, w]);
  return maps;
}

/** Bytes of the feature maps of a workspace (what `allocUNetWorkspace` carves from an arena). */
export function unetWorkspaceBytes(weights: UNetWeights, h: number, w: number): number {
  let bytes = 0;
  for (const [c, mh, mw] of workspaceMaps(weights, h, w)) bytes += planesBytes(c, mh, mw);
  return bytes;
}

/**
 * A workspace for h × w tiles. With `shared` (unetWorkspaceBytes of it), the feature maps
 * are views of that memory, so threads that each allocate a workspace on the same buffer
 * share the maps and can run one tile together in bands (`runUNet`); the Winograd scratch
 * is always the thread's own.
 */
export function allocUNetWorkspace(
  weights: UNetWeights,
  h: number,
  w: number,
  shared?: ArrayBufferLike,
): UNetWorkspace {
  const arena = shared ? { buffer: shared, offset: 0 } : undefined;
  const maps = workspaceMaps(weights, h, w).map(([c, mh, mw]) => allocPlanes(c, mh, mw, arena));
  const x = [0, 1, 2, 3, 4].map((k) => [maps[2 * k]!, maps[2 * k + 1]!] as const);
  const pool = maps.slice(10, 14);
  const input = maps[14]!;
  const winograd = allocWinogradScratch(
    Math.max(...weights.layers.map((l) => l.inChannels)),
    Math.max(...weights.layers.map((l) => l.outChannels)),
  );
  return { h, w, input, output: x[0]![1], x, pool, winograd };
}

function byName(weights: UNetWeights): (n: string) => ConvLayer {
  return (n) => {
    const l = weights.layers.find((layer) => layer.name === n);
    if (!l) throw new RangeError(`U-Net has no layer ${n}`);
    return l;
  };
}

/**
 * One of `count` threads that run a tile together on a shared workspace: each computes
 * its band of every layer's rows, and `sync` (a barrier) returns once all of them have
 * finished the layer. Every value is computed as it is by one thread (a Winograd block,
 * a pooled or upsampled pixel, a direct convolution's row), so the bits do not depend on
 * the number of threads.
 */
export interface UNetBand {
  readonly index: number;
  readonly count: number;
  readonly sync: () => void;
}

/** The rows [from, to) of n that band `band` computes (all of them without a band). */
export function bandRows(n: number, band?: UNetBand): [number, number] {
  if (!band) return [0, n];
  return [
    Math.floor((n * band.index) / band.count),
    Math.floor((n * (band.index + 1)) / band.count),
  ];
}

/**
 * Runs the network on ws.input; the result is in ws.output (channels 0–2). `stop`, when
 * given, is asked between layers: the pass ends early (returning false, the output
 * undefined) once it answers true, so a caller can drop a picture no longer wanted.
 * With `band`, this thread computes its band of every layer (UNetBand); a band cannot stop.
 */
export function runUNet(
  weights: UNetWeights,
  ws: UNetWorkspace,
  stop?: () => boolean,
  band?: UNetBand,
): boolean {
  // A band that stopped alone would leave the others waiting at the next barrier.
  if (band && stop) throw new RangeError('runUNet: a band cannot stop early');
  const [e0, e1, e2, e3, e4, e5a, e5b, d4a, d4b, d3a, d3b, d2a, d2b, d1a, d1b, d0] =
    weights.layers as [
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
      ConvLayer,
    ];
  const [x0, x1, x2, x3, x4] = ws.x as [
    readonly [Planes, Planes],
    readonly [Planes, Planes],
    readonly [Planes, Planes],
    readonly [Planes, Planes],
    readonly [Planes, Planes],
  ];
  const [p1, p2, p3, p4] = ws.pool as [Planes, Planes, Planes, Planes];
  // Winograd where the outputs come in fours (every layer but dec_conv0's 3); the direct
  // convolution for the rest, where the transforms would cost more than they save.
  const sync = band ? band.sync : () => {};
  const conv = (a: Planes, b: Planes | null, layer: ConvLayer, dst: Planes): void => {
    if (winogradFits(layer)) {
      const [r0, r1] = bandRows(winogradRows(dst.h), band);
      winogradConv3x3Relu(a, b, layer, dst, ws.winograd, r0, r1);
    } else {
      const [y0, y1] = bandRows(dst.h, band);
      conv3x3Relu(a, b, layer, dst, y0, y1);
    }
    sync();
  };
  const pool = (src: Planes, dst: Planes): void => {
    const [y0, y1] = bandRows(dst.h, band);
    maxPool2x2(src, dst, y0, y1);
    sync();
  };
  const up = (src: Planes, dst: Planes): void => {
    const [y0, y1] = bandRows(src.h, band);
    upsample2x(src, dst, y0, y1);
    sync();
  };
  const steps: (() => void)[] = [
    // Encoder.
    () => conv(ws.input, null, e0, x0[0]),
    () => conv(x0[0], null, e1, x0[1]),
    () => {
      pool(x0[1], p1);
      conv(p1, null, e2, x1[0]);
    },
    () => {
      pool(x1[0], p2);
      conv(p2, null, e3, x2[0]);
    },
    () => {
      pool(x2[0], p3);
      conv(p3, null, e4, x3[0]);
    },
    () => {
      pool(x3[0], p4);
      conv(p4, null, e5a, x4[0]);
      conv(x4[0], null, e5b, x4[1]);
    },
    // Decoder: upsample, then convolve [upsampled, skip].
    () => {
      up(x4[1], x3[0]);
      conv(x3[0], p3, d4a, x3[1]);
      conv(x3[1], null, d4b, x3[0]);
    },
    () => {
      up(x3[0], x2[0]);
      conv(x2[0], p2, d3a, x2[1]);
    },
    () => conv(x2[1], null, d3b, x2[0]),
    () => {
      up(x2[0], x1[0]);
      conv(x1[0], p1, d2a, x1[1]);
    },
    () => conv(x1[1], null, d2b, x1[0]),
    () => {
      up(x1[0], x0[0]);
      conv(x0[0], ws.input, d1a, x0[1]);
    },
    () => conv(x0[1], null, d1b, x0[0]),
    () => conv(x0[0], null, d0, x0[1]),
  ];
  for (const step of steps) {
    if (stop?.()) return false;
    step();
  }
  return true;
}
