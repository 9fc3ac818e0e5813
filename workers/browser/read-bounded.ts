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

/**
 * Longest stretch of reading in one task (ms). A body that has arrived already
 * resolves every read at once, so the loop would otherwise run to the end in one task:
 * 6 MB took ~80 ms of the page's thread (several times that on a loaded machine).
 */
const SLICE_MS = 8;
/** Most a Content-Length header may make the reader allocate before the bytes arrive. */
const PREALLOCATE_MAX = 64 * 1024 * 1024;

/** A new task soon (scheduler.yield where there is one: a timeout's 4 ms clamp is not). */
function nextTask(): Promise<void> {
  const scheduler = (globalThis as { scheduler?: { yield?: () => Promise<void> } }).scheduler;
  if (typeof scheduler?.yield === 'function') return scheduler.yield();
  return new Promise((resolve) => setTimeout(resolve, 0));
}

/**
 * The body of `response`, at most `limit` bytes; throws ByteLimitError past it. The
 * bytes are copied into one buffer as they come (sized by Content-Length when it says,
 * which a lying header only makes grow or shrink), in slices of at most SLICE_MS.
 */
export async function readResponseBounded(response: Response, limit: number): Promise<Uint8Array> {
  if (response.body === null) return new Uint8Array(0);
  const reader = response.body.getReader();
  const declared = Number(response.headers.get('content-length') ?? NaN);
  const sized = Number.isSafeInteger(declared) && declared > 0 && declared <= limit;
  let out = new Uint8Array(sized ? Math.min(declared, PREALLOCATE_MAX) : 64 * 1024);
  let total = 0;
  let sliceStart = performance.now();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    if (value.length > limit - total) {
      await reader.cancel().catch(() => undefined);
      throw new ByteLimitError(total + value.length, false, limit);
    }
    if (total + value.length > out.length) {
      const grown = new Uint8Array(Math.min(limit, Math.max(2 * out.length, total + value.length)));
      grown.set(out.subarray(0, total));
      out = grown;
    }
    out.set(value, total);
    total += value.length;
    if (performance.now() - sliceStart > SLICE_MS) {
      await nextTask();
      sliceStart = performance.now();
    }
  }
  return total === out.length ? out : out.slice(0, total);
}

/** The bytes of a Blob (a File), at most `limit`; its size is checked before reading. */
export async function readBlobBounded(blob: Blob, limit: number): Promise<Uint8Array> {
  if (blob.size > limit) throw new ByteLimitError(blob.size, true, limit);
  return new Uint8Array(await blob.arrayBuffer());
}
