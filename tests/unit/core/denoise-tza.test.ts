import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { halfToFloat, parseTza } from '../../../src/core/denoise/tza.ts';
import { unetWeights } from '../../../src/core/denoise/unet-weights.ts';
import { FormatError } from '../../../src/core/util/format-error.ts';
import { tinyUNetTza, writeTza } from '../../helpers/tza.ts';

const vendor = new URL('../../../vendor/oidn-weights/', import.meta.url);

function refusal(bytes: Uint8Array): string {
  try {
    parseTza(bytes);
  } catch (e) {
    expect(e).toBeInstanceOf(FormatError);
    return (e as Error).message;
  }
  throw new Error('parsed a malformed file');
}

describe('TZA (OIDN tensor archive)', () => {
  it('reads the shipped OIDN 2.5 weights with the RT U-Net shapes', () => {
    const t = parseTza(readFileSync(new URL('rt_hdr_alb_nrm.tza', vendor)));
    expect(t.size).toBe(32);
    expect(t.get('enc_conv0.weight')!.shape).toEqual([32, 9, 3, 3]);
    expect(t.get('dec_conv1a.weight')!.shape).toEqual([64, 73, 3, 3]);
    expect(t.get('dec_conv0.bias')!.layout).toBe('x');
    expect(unetWeights(t).inputChannels).toBe(9);
    expect(unetWeights(parseTza(readFileSync(new URL('rt_hdr.tza', vendor)))).inputChannels).toBe(
      3,
    );
  });

  it('widens half floats exactly', () => {
    expect(halfToFloat(0x3c00)).toBe(1);
    expect(halfToFloat(0xc000)).toBe(-2);
    expect(halfToFloat(0x7bff)).toBe(65504);
    expect(halfToFloat(0x0001)).toBe(2 ** -24);
    expect(halfToFloat(0x3555)).toBe(0.333251953125);
    expect(halfToFloat(0x7c00)).toBe(Infinity);
    expect(Number.isNaN(halfToFloat(0x7e00))).toBe(true);
  });

  it('round-trips float32 and float16 tensors', () => {
    const t = parseTza(
      writeTza([
        { name: 'a', shape: [2, 3], layout: 'ab', dtype: 'f', values: [1, 2, 3, 4, 5, 0.1] },
        { name: 'b', shape: [2], layout: 'x', dtype: 'h', values: [0.5, -3] },
      ]),
    );
    expect([...t.get('a')!.data]).toEqual([1, 2, 3, 4, 5, Math.fround(0.1)]);
    expect([...t.get('b')!.data]).toEqual([0.5, -3]);
  });

  it('refuses malformed files with one FormatError naming the problem', () => {
    const good = writeTza([{ name: 'w', shape: [4], layout: 'x', values: [1, 2, 3, 4] }]);
    const patch = (at: number, bytes: number[]): Uint8Array => {
      const b = good.slice();
      b.set(bytes, at);
      return b;
    };
    const table = new DataView(good.buffer).getUint32(4, true);
    expect(refusal(new Uint8Array(5))).toMatch(/ends inside the header/);
    expect(refusal(patch(0, [0, 0]))).toMatch(/bad magic/);
    expect(refusal(patch(2, [3]))).toMatch(/version 3/);
    expect(refusal(patch(4, [0xff, 0xff, 0xff, 0x7f]))).toMatch(/table offset/);
    expect(refusal(good.slice(0, good.length - 3))).toMatch(/ends inside tensor "w"'s data offset/);
    expect(refusal(patch(table, [0xff, 0xff, 0, 0]))).toMatch(/65535 tensors/);
    expect(refusal(patch(table + 4, [0, 0]))).toMatch(/name has length 0/);
    expect(refusal(patch(table + 6, [7]))).toMatch(/non-printable/);
    expect(refusal(patch(table + 7, [0]))).toMatch(/0 dimensions/);
    expect(refusal(patch(table + 8, [0xff, 0xff, 0xff, 0x0f]))).toMatch(
      /more elements than the file has bytes/,
    );
    expect(refusal(patch(table + 13, ['d'.charCodeAt(0)]))).toMatch(/data type 'd'/);
    expect(refusal(patch(table + 14, [0xf0, 0xff]))).toMatch(/outside the file/);
    const twice = writeTza([
      { name: 'w', shape: [1], layout: 'x', values: [1] },
      { name: 'w', shape: [1], layout: 'x', values: [1] },
    ]);
    expect(refusal(twice)).toMatch(/"w" appears twice/);
    expect(
      refusal(writeTza([{ name: 'w', shape: [1], layout: 'x', dtype: 'f', values: [NaN] }])),
    ).toMatch(/non-finite/);
  });

  it('refuses weights that are not the RT U-Net', () => {
    const t = parseTza(tinyUNetTza(9, 4, 1));
    expect(unetWeights(t).layers.length).toBe(16);
    const missing = new Map(t);
    missing.delete('dec_conv2b.bias');
    expect(() => unetWeights(missing)).toThrow(/missing tensor "dec_conv2b.bias"/);
    const wrong = new Map(t);
    wrong.set('enc_conv2.weight', { ...t.get('enc_conv2.weight')!, shape: [4, 5, 3, 3] });
    expect(() => unetWeights(wrong)).toThrow(
      /"enc_conv2.weight" takes 5 channels, the network gives it 4/,
    );
    expect(() => unetWeights(parseTza(tinyUNetTza(4, 4, 1)))).toThrow(/enc_conv0 takes 4 channels/);
  });
});
