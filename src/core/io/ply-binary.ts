/** The body of a binary PLY file (little- or big-endian): values read in order. */
import { FormatError } from './format-error.ts';
import { SIZE, type Element, type Reader } from './ply-header.ts';

export class BinaryBody implements Reader {
  private pos: number;
  constructor(
    private readonly view: DataView,
    private readonly start: number,
    private readonly little: boolean,
    private readonly limit: number,
  ) {
    this.pos = start;
  }

  rewind(): void {
    this.pos = this.start;
  }

  where(): string {
    return '';
  }

  // A binary body has no lines: an instance is its values, back to back.
  begin(): void {}
  end(): void {}
  finish(): void {}

  value(type: number, element: Element, index: number): number {
    const p = this.pos;
    const size = SIZE[type];
    if (p + size > this.limit) {
      throw new FormatError(
        'PLY',
        `the file ends in ${element.name} ${index} of the ${element.count} the header declares`,
      );
    }
    this.pos = p + size;
    const v = this.view;
    switch (type) {
      case 0:
        return v.getInt8(p);
      case 1:
        return v.getUint8(p);
      case 2:
        return v.getInt16(p, this.little);
      case 3:
        return v.getUint16(p, this.little);
      case 4:
        return v.getInt32(p, this.little);
      case 5:
        return v.getUint32(p, this.little);
      case 6:
        return v.getFloat32(p, this.little);
      default:
        return v.getFloat64(p, this.little);
    }
  }
}
