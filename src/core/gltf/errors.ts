/**
 * The one error a glTF file gets: a FormatError of format "glTF" (the
 * contract of every file decoder, src/core/io/format-error.ts) whose one
 * printable line names the place in the file (`accessors[3]`,
 * `meshes[0].primitives[1]`, `GLB header`) and the problem. The scene
 * loader prefixes the shape and the file name.
 */
import { FormatError } from '../io/format-error.ts';

export class GltfError extends FormatError {
  override name = 'GltfError';
  constructor(message: string) {
    super('glTF', message);
  }
}

/** The message of anything thrown (an Error, a DOMException, a string). */
export function messageOf(e: unknown): string {
  return e instanceof Error ? e.message : String(e);
}
