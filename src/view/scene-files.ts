/**
 * The page's SceneFileReaders: those that also work in a worker
 * (workers/scene-files.ts), and files from a table of bundled asset URLs.
 */
import type { SceneFileReader } from '../core/index.ts';
import { urlSceneFiles } from '../../workers/scene-files.ts';

export {
  droppedSceneFiles,
  urlSceneFiles,
  type FileSource,
  type PortableReader,
} from '../../workers/scene-files.ts';

/**
 * Files from a table of URLs, by the path the scene names them with: for scenes whose
 * files a bundler moved (the demo's presets, whose assets get hashed names).
 */
export function mappedSceneFiles(urls: Record<string, string>): SceneFileReader {
  const byUrl = urlSceneFiles(document.baseURI);
  return {
    read(path: string, maxBytes: number): Promise<Uint8Array> {
      const url = Object.hasOwn(urls, path) ? urls[path] : undefined;
      if (url === undefined) return Promise.reject(new Error('it is not among the known files'));
      return byUrl.read(url, maxBytes);
    },
  };
}
