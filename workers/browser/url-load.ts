/**
 * Fetching a scene or model by URL, in the scene worker (model-worker.ts) or, where
 * that worker cannot start, on the page: one bounded read with the same messages in
 * both places. In the worker the page never holds the bytes: a 6 MB scene received on
 * the page cost it ~80 ms of native work in one task before any script saw a byte.
 */
import {
  GLTF_FILE_BYTES,
  isGlbBytes,
  isModelFileName,
  LIMITS,
  type LoadStage,
  sceneSizeProblem,
} from '../../src/core/index.ts';
import { ByteLimitError, readResponseBounded } from './read-bounded.ts';
import { urlSceneFiles, type PortableReader } from './scene-files.ts';

export interface Fetched {
  bytes: Uint8Array;
  /** The URL the body came from (after redirects): the files it names live beside it. */
  base: string;
  /** The URL names a .glb / .gltf model (read with the model's byte bound). */
  model: boolean;
}

export function modelSizeProblem(size: number, exact: boolean): string {
  const got = exact ? `${size}` : `at least ${size}`;
  return `a glTF model must be at most ${GLTF_FILE_BYTES} bytes (1 GiB), got ${got} bytes`;
}

/** The last component of a URL's path, as its file's name. */
export function fileNameOf(url: string): string {
  const last = new URL(url).pathname.replace(/^.*\//, '');
  try {
    return decodeURIComponent(last) || 'model.glb';
  } catch {
    return last || 'model.glb';
  }
}

/**
 * Fetches `href` (absolute) with the byte bound of a scene file, or of a model when
 * its path names one. Errors are one line led by `label` (the URL as the caller wrote
 * it): an HTTP status, a size past the bound; a network failure is fetch's own.
 */
export async function fetchBounded(
  href: string,
  label: string,
  onProgress: (stage: LoadStage, done: number, total: number) => void,
  signal?: AbortSignal,
): Promise<Fetched> {
  let model = false;
  try {
    model = isModelFileName(new URL(href).pathname);
  } catch {
    // Not a URL: fetch says so below.
  }
  try {
    if (model) onProgress('read', 0, 1);
    const response = await fetch(href, signal ? { signal } : undefined);
    if (!response.ok) throw new Error(`${label}: HTTP ${response.status}`);
    const base = response.url || href;
    const bytes = await readResponseBounded(response, model ? GLTF_FILE_BYTES : LIMITS.fileBytes);
    if (model) onProgress('read', 1, 1);
    return { bytes, base, model };
  } catch (e) {
    if (!(e instanceof ByteLimitError)) throw e;
    const size = model ? modelSizeProblem(e.size, e.exact) : sceneSizeProblem(e.size, e.exact);
    throw new Error(`${label}: ${size}`);
  }
}

/**
 * What a fetched URL is, read by the caller's loaders: a bare model when its path names
 * one or its bytes are a GLB (its loader's errors led by the file's name), else a
 * pathwise-scene/1 file. The files either names are read beside it. One rule for the
 * scene worker and for the page that loads without it.
 */
export async function readFetched<T>(
  fetched: Fetched,
  readModel: (bytes: Uint8Array, name: string, files: PortableReader) => Promise<T>,
  readScene: (bytes: Uint8Array, files: PortableReader) => Promise<T>,
): Promise<T> {
  const { bytes, base, model } = fetched;
  const files = urlSceneFiles(base);
  if (!model && !isGlbBytes(bytes)) return readScene(bytes, files);
  const name = fileNameOf(base);
  try {
    return await readModel(bytes, name, files);
  } catch (e) {
    throw new Error(`${name}: ${e instanceof Error ? e.message : String(e)}`);
  }
}
