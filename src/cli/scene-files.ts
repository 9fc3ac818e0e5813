/**
 * The command line's SceneFileReader: the files a scene names, relative to the scene
 * file's folder, read with a bound whatever their source (read-bounded.ts), so a device
 * or a pipe named as a mesh cannot make it read without end.
 *
 * Every file it reads lies inside the scene's folder (for a bare model, the model's
 * folder) or inside a folder given with `--allow-read`, once links are resolved: the
 * real path of the file must lie under the real path of one of those folders. So a
 * scene or a model from someone else cannot make a render read `../secret`,
 * `/etc/passwd`, or a link beside it that points out (docs/gltf.md, "Files a model may
 * read"). A glTF model's URIs are also checked by name in the core (core/gltf/io.ts),
 * where `allowedFolders` widens that check the same way.
 */
import { realpath } from 'node:fs/promises';
import { isAbsolute, relative, resolve, sep } from 'node:path';
import type { SceneFileReader } from '../core/scene/load/load.ts';
import { ReadLimitError, readBounded, showPath } from './read-bounded.ts';

export interface SceneFilesOptions {
  /** More folders whose files may be read (`--allow-read`), absolute or relative to the working directory. */
  allowRead?: readonly string[];
}

export function nodeSceneFiles(sceneDir: string, options: SceneFilesOptions = {}): SceneFileReader {
  const allowRead = (options.allowRead ?? []).map((d) => resolve(d));
  let roots: Promise<string[]> | null = null;
  // Real paths of the folders, once: a folder that does not exist holds no file.
  const realRoots = (): Promise<string[]> =>
    (roots ??= Promise.all(
      [resolve(sceneDir), ...allowRead].map((d) => realpath(d).catch(() => null)),
    ).then((list) => list.filter((d): d is string => d !== null)));
  return {
    // For the core's check of a model's URIs by name: the folders as paths relative to
    // the scene's folder (absolute where no relative path leads there, as across drives),
    // normalized as relative() makes them; '' (the scene's own folder) widens nothing.
    allowedFolders: allowRead.map((d) => {
      const rel = relative(resolve(sceneDir), d).split(sep).join('/');
      return isAbsolute(rel) ? d.split(sep).join('/') : rel;
    }),
    async read(path: string, maxBytes: number): Promise<Uint8Array> {
      const full = isAbsolute(path) ? path : resolve(sceneDir, path);
      let real: string | null = null;
      try {
        real = await realpath(full);
      } catch {
        // A missing or unreadable file: readBounded says why, in its own words.
      }
      if (real !== null && !(await realRoots()).some((root) => isUnder(real!, root))) {
        const resolved = real === full ? '' : ` (through a link, to ${showPath(real)})`;
        throw new Error(
          `the file lies outside the scene's folder${resolved}; only files beside the scene ` +
            'or the model are read, add --allow-read FOLDER to read others',
        );
      }
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

function isUnder(path: string, root: string): boolean {
  return path === root || path.startsWith(root.endsWith(sep) ? root : root + sep);
}
