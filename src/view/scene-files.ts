/**
 * The page's own SceneFileReader (those that also work in a worker are in
 * workers/browser/scene-files.ts): files from a table of bundled asset URLs.
 */
import type { SceneFileReader } from '../core/index.ts';
import { urlSceneFiles } from '../../workers/browser/scene-files.ts';

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
