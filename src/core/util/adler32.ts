/**
 * Adler-32 (RFC 1950 §8.2), the checksum that ends a zlib stream: the PNG
 * encoder writes it, and the checked inflate of png-data.ts verifies it
 * (fflate does not). Continues from `adler` (1 to start), so a stream can be
 * summed in pieces.
 */
export function adler32(bytes: Uint8Array, adler = 1): number {
  let a = adler & 0xffff;
  let b = adler >>> 16;
  // Reduced every 5552 bytes at most (zlib's NMAX), so the sums stay exact doubles.
  for (let i = 0; i < bytes.length;) {
    const end = Math.min(bytes.length, i + 5552);
    for (; i < end; i++) {
      a += bytes[i];
      b += a;
    }
    a %= 65521;
    b %= 65521;
  }
  return ((b << 16) | a) >>> 0;
}
