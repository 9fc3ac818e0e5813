/**
 * How a failed image decode reads to a user: "cannot decode PNG: <what is wrong in the
 * file>" (issue 27, deliverable 4), whoever decoded it (fast-png, jpeg-js, the
 * browser's createImageBitmap) and whichever check caught it.
 */
import { FormatError } from '../util/format-error.ts';
import { sanitize } from '../util/message.ts';

/**
 * A decoding library's message when it speaks about the file; JavaScript's own
 * (a TypeError or RangeError from reading past what the library expected) says
 * nothing to a user, so it is replaced.
 */
export function libraryMessage(e: unknown): string {
  // An allocation the engine refused is not the file's fault in the same way: said so.
  if (
    e instanceof RangeError &&
    /allocation failed|Invalid (typed )?array length/.test(e.message)
  ) {
    return 'out of memory while decoding';
  }
  if (e instanceof Error && !(e instanceof TypeError) && !(e instanceof RangeError)) {
    return sanitize(e.message, 80);
  }
  return 'the decoder stopped on malformed data';
}

/**
 * The one message of a failed image decode: "cannot decode PNG: <what is wrong>". The
 * caller prefixes the image's name.
 */
export function imageDecodeError(e: unknown): Error {
  if (e instanceof FormatError) {
    const detail = e.message.startsWith(`${e.format}: `)
      ? e.message.slice(e.format.length + 2)
      : e.message;
    return new Error(`cannot decode ${e.format}: ${detail}`);
  }
  return new Error(`cannot decode the image: ${libraryMessage(e)}`);
}
