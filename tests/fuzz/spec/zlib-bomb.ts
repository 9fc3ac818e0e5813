/**
 * A zlib stream (RFC 1950) of `mib` MiB of zero bytes built without ever holding them: one
 * deflate block sequence of 1 MiB of zeros ended by a full flush (byte-aligned, no
 * dictionary reference across it, RFC 1951 §3.2.3), repeated, then an empty final stored
 * block and the Adler-32 of the whole, which for n zeros is a = 1, b = n mod 65521.
 */
import { constants, deflateRawSync } from 'node:zlib';
import { concat } from './bytes.ts';

let block: Uint8Array | undefined;

export function zeroBomb(mib: number): Uint8Array {
  block ??= deflateRawSync(new Uint8Array(1 << 20), {
    level: 9,
    finishFlush: constants.Z_FULL_FLUSH,
  });
  const n = mib * 2 ** 20;
  const b = n % 65521;
  const adler = new Uint8Array([(b >> 8) & 0xff, b & 0xff, 0, 1]);
  const finalStored = new Uint8Array([0x01, 0x00, 0x00, 0xff, 0xff]);
  return concat([
    new Uint8Array([0x78, 0xda]),
    ...Array.from({ length: mib }, () => block!),
    finalStored,
    adler,
  ]);
}
