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
import { allocPlanes, type Planes } from './planes.ts';
import { maxPool2x2, upsample2x } from './pool-upsample.ts';
import type { ConvLayer, UNetWeights } from './unet-weights.ts';
import {
  allocWinogradScratch,
  winogradConv3x3Relu,
  winogradFits,
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

export function allocUNetWorkspace(weights: UNetWeights, h: number, w: number): UNetWorkspace {
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
  const x = width.map(
    (c, k) => [allocPlanes(c, h >> k, w >> k), allocPlanes(c, h >> k, w >> k)] as const,
  );
  const pool = [
    allocPlanes(out('enc_conv1'), h >> 1, w >> 1),
    allocPlanes(out('enc_conv2'), h >> 2, w >> 2),
    allocPlanes(out('enc_conv3'), h >> 3, w >> 3),
    allocPlanes(out('enc_conv4'), h >> 4, w >> 4),
  ];
  const input = allocPlanes(weights.inputChannels, h, w);
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
 * Runs the network on ws.input; the result is in ws.output (channels 0–2). `stop`, when
 * given, is asked between layers: the pass ends early (returning false, the output
 * undefined) once it answers true, so a caller can drop a picture no longer wanted.
 */
export function runUNet(weights: UNetWeights, ws: UNetWorkspace, stop?: () => boolean): boolean {
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
  const conv = (a: Planes, b: Planes | null, layer: ConvLayer, dst: Planes): void =>
    winogradFits(layer)
      ? winogradConv3x3Relu(a, b, layer, dst, ws.winograd)
      : conv3x3Relu(a, b, layer, dst);
  const steps: (() => void)[] = [
    // Encoder.
    () => conv(ws.input, null, e0, x0[0]),
    () => conv(x0[0], null, e1, x0[1]),
    () => {
      maxPool2x2(x0[1], p1);
      conv(p1, null, e2, x1[0]);
    },
    () => {
      maxPool2x2(x1[0], p2);
      conv(p2, null, e3, x2[0]);
    },
    () => {
      maxPool2x2(x2[0], p3);
      conv(p3, null, e4, x3[0]);
    },
    () => {
      maxPool2x2(x3[0], p4);
      conv(p4, null, e5a, x4[0]);
      conv(x4[0], null, e5b, x4[1]);
    },
    // Decoder: upsample, then convolve [upsampled, skip].
    () => {
      upsample2x(x4[1], x3[0]);
      conv(x3[0], p3, d4a, x3[1]);
      conv(x3[1], null, d4b, x3[0]);
    },
    () => {
      upsample2x(x3[0], x2[0]);
      conv(x2[0], p2, d3a, x2[1]);
    },
    () => conv(x2[1], null, d3b, x2[0]),
    () => {
      upsample2x(x2[0], x1[0]);
      conv(x1[0], p1, d2a, x1[1]);
    },
    () => conv(x1[1], null, d2b, x1[0]),
    () => {
      upsample2x(x1[0], x0[0]);
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
