/**
 * The "RT" U-Net's convolutions, by the names OIDN gives them (core/unet_filter.cpp,
 * addUNet; training/model.py, UNet), checked against a TZA file's tensors. Each layer is
 * a 3×3 convolution with bias and ReLU; the shapes chain as the network wires them:
 *
 *   enc_conv0  in → 32            full resolution
 *   enc_conv1  → pool1 (½)        enc_conv2 → pool2 (¼)   enc_conv3 → pool3 (⅛)
 *   enc_conv4  → pool4 (1/16)     enc_conv5a, enc_conv5b → upsample ×2
 *   dec_conv4a [up, pool3] → dec_conv4b → upsample   dec_conv3a [up, pool2] → dec_conv3b → up
 *   dec_conv2a [up, pool1] → dec_conv2b → upsample   dec_conv1a [up, input] → dec_conv1b
 *   dec_conv0  → 3 channels
 *
 * Only the base network is supported ("_small" files have the same layers, narrower; the
 * "_large" network, enc_conv1a/1b…, is refused by name).
 */
import { FormatError } from '../util/format-error.ts';
import type { TzaTensor } from './tza.ts';

export interface ConvLayer {
  readonly name: string;
  readonly inChannels: number;
  readonly outChannels: number;
  /** [outChannels][inChannels][3][3], row-major (OIDN's "oihw"). */
  readonly weight: Float32Array;
  readonly bias: Float32Array;
}

/** The layers in execution order. */
export const UNET_LAYER_NAMES = [
  'enc_conv0',
  'enc_conv1',
  'enc_conv2',
  'enc_conv3',
  'enc_conv4',
  'enc_conv5a',
  'enc_conv5b',
  'dec_conv4a',
  'dec_conv4b',
  'dec_conv3a',
  'dec_conv3b',
  'dec_conv2a',
  'dec_conv2b',
  'dec_conv1a',
  'dec_conv1b',
  'dec_conv0',
] as const;

export interface UNetWeights {
  /** Input channels: 3 (colour), 6 (+ albedo) or 9 (+ albedo + normal). */
  readonly inputChannels: number;
  readonly layers: readonly ConvLayer[];
}

function fail(detail: string): never {
  throw new FormatError('TZA', detail);
}

function layer(tensors: Map<string, TzaTensor>, name: string): ConvLayer {
  const w = tensors.get(`${name}.weight`);
  const b = tensors.get(`${name}.bias`);
  if (!w) fail(`missing tensor "${name}.weight" (not an OIDN "RT" U-Net)`);
  if (!b) fail(`missing tensor "${name}.bias"`);
  const [o, i, kh, kw] = w.shape;
  if (w.layout !== 'oihw' || w.shape.length !== 4 || kh !== 3 || kw !== 3)
    fail(`"${name}.weight" is ${w.layout} [${w.shape.join(', ')}], expected oihw [out, in, 3, 3]`);
  if (b.shape.length !== 1 || b.shape[0] !== o)
    fail(`"${name}.bias" has shape [${b.shape.join(', ')}], expected [${o}]`);
  return { name, inChannels: i!, outChannels: o!, weight: w.data, bias: b.data };
}

/** Builds the network's layers from parsed TZA tensors, checking that every shape chains. */
export function unetWeights(tensors: Map<string, TzaTensor>): UNetWeights {
  if (tensors.has('enc_conv1b.weight')) fail('the large U-Net (enc_conv1b) is not supported');
  const layers = UNET_LAYER_NAMES.map((n) => layer(tensors, n));
  const by = (n: (typeof UNET_LAYER_NAMES)[number]): ConvLayer =>
    layers[UNET_LAYER_NAMES.indexOf(n)]!;
  const inputChannels = by('enc_conv0').inChannels;
  if (inputChannels !== 3 && inputChannels !== 6 && inputChannels !== 9)
    fail(`enc_conv0 takes ${inputChannels} channels (expected 3, 6 or 9)`);
  // What each layer reads: the previous layer's output, plus a skip connection for the "a" decoders.
  const expectIn: [string, number][] = [
    ['enc_conv1', by('enc_conv0').outChannels],
    ['enc_conv2', by('enc_conv1').outChannels],
    ['enc_conv3', by('enc_conv2').outChannels],
    ['enc_conv4', by('enc_conv3').outChannels],
    ['enc_conv5a', by('enc_conv4').outChannels],
    ['enc_conv5b', by('enc_conv5a').outChannels],
    ['dec_conv4a', by('enc_conv5b').outChannels + by('enc_conv3').outChannels],
    ['dec_conv4b', by('dec_conv4a').outChannels],
    ['dec_conv3a', by('dec_conv4b').outChannels + by('enc_conv2').outChannels],
    ['dec_conv3b', by('dec_conv3a').outChannels],
    ['dec_conv2a', by('dec_conv3b').outChannels + by('enc_conv1').outChannels],
    ['dec_conv2b', by('dec_conv2a').outChannels],
    ['dec_conv1a', by('dec_conv2b').outChannels + inputChannels],
    ['dec_conv1b', by('dec_conv1a').outChannels],
    ['dec_conv0', by('dec_conv1b').outChannels],
  ];
  for (const [n, c] of expectIn) {
    const l = by(n as (typeof UNET_LAYER_NAMES)[number]);
    if (l.inChannels !== c)
      fail(`"${n}.weight" takes ${l.inChannels} channels, the network gives it ${c}`);
  }
  if (by('dec_conv0').outChannels !== 3)
    fail(`dec_conv0 gives ${by('dec_conv0').outChannels} channels (expected 3)`);
  return { inputChannels, layers };
}
