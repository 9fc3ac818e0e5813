/**
 * The error of every file decoder (PFM here; OBJ, PLY, HDR, glTF and film files alike): a
 * file that is truncated, whose header lies, or whose data holds NaN is rejected with one
 * printable line that names the format and where in the file the problem is. Decoders
 * never throw anything else on bad bytes (no RangeError from a DataView, no allocation
 * sized by an unchecked header): tests/fuzz/formats.test.ts checks that contract for each
 * format in its table.
 */
import { printableLine } from './message.ts';

export class FormatError extends Error {
  override name = 'FormatError';
  /** Short name of the format, e.g. "PFM". */
  readonly format: string;

  constructor(format: string, detail: string) {
    super(printableLine(`${format}: ${detail}`, 400));
    this.format = format;
  }
}
