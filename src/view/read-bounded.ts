/**
 * Reading a scene (or any input file) in the browser with the same byte bound as the
 * command line: a fetched body is read as a stream and counted, so a server that sends
 * an endless or huge body (or a lying Content-Length) costs at most limit + one chunk; a
 * dropped or picked File reports its size, which is checked before reading it.
 */

/** The input is larger than the limit. */
export class ByteLimitError extends Error {
  override name = 'ByteLimitError';

  constructor(
    /** Size in bytes: exact when `exact`, else what was read before stopping. */
    readonly size: number,
    readonly exact: boolean,
    readonly limit: number,
  ) {
    super(`input is larger than the limit of ${limit} bytes`);
  }
}

/** The body of `response`, at most `limit` bytes; throws ByteLimitError past it. */
export async function readResponseBounded(response: Response, limit: number): Promise<Uint8Array> {
  if (response.body === null) return new Uint8Array(0);
  const reader = response.body.getReader();
  const chunks: Uint8Array[] = [];
  let total = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    total += value.length;
    if (total > limit) {
      await reader.cancel().catch(() => undefined);
      throw new ByteLimitError(total, false, limit);
    }
    chunks.push(value);
  }
  const out = new Uint8Array(total);
  let at = 0;
  for (const chunk of chunks) {
    out.set(chunk, at);
    at += chunk.length;
  }
  return out;
}

/** The bytes of a Blob (a File), at most `limit`; its size is checked before reading. */
export async function readBlobBounded(blob: Blob, limit: number): Promise<Uint8Array> {
  if (blob.size > limit) throw new ByteLimitError(blob.size, true, limit);
  return new Uint8Array(await blob.arrayBuffer());
}
