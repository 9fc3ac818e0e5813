/**
 * The command line's SceneFileReader: the files a scene names, relative to the scene
 * file's folder, read with a bound whatever their source (read-bounded.ts), so a device
 * or a pipe named as a mesh cannot make it read without end.
 */
import { isAbsolute, resolve } from 'node:path';
import type { SceneFileReader } from '../core/scene/load/load.ts';
import { ReadLimitError, readBounded } from './read-bounded.ts';

export function nodeSceneFiles(sceneDir: string): SceneFileReader {
  return {
    async read(path: string, maxBytes: number): Promise<Uint8Array> {
      const full = isAbsolute(path) ? path : resolve(sceneDir, path);
      try {
        return await readBounded(full, maxBytes);
      } catch (e) {
        if (e instanceof ReadLimitError) {
          throw new Error(
            e.exact
              ? `the file has ${e.size} bytes, more than the limit of ${e.limit}`
              : `the file has more than the limit of ${e.limit} bytes`,
          );
        }
        throw e;
      }
    },
  };
}
