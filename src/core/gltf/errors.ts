/**
 * The one error a glTF file gets: a single printable line naming the place
 * in the file (`accessors[3]`, `meshes[0].primitives[1]`, `GLB header`) and
 * the problem. The scene loader prefixes the shape and the file name.
 */
import { printableLine } from '../scene/message.ts';

export class GltfError extends Error {
  override name = 'GltfError';
  constructor(message: string) {
    super(printableLine(message));
  }
}
