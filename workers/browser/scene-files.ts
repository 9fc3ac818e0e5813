/**
 * The browser's SceneFileReaders (core/scene/load/load.ts): the files a scene names are
 * fetched relative to the scene's URL, or taken from the files dropped together with
 * the scene — on the page or in a worker (fetch and File work in both). A URL stays
 * on the scene's origin (urlInside). Both refuse a file over the reader's byte limit before holding it whole:
 * by its declared size (Content-Length, File.size), and while streaming by the bytes
 * actually received.
 */
import type { SceneFileReader } from '../../src/core/index.ts';
import { ByteLimitError, readResponseBounded } from './read-bounded.ts';

/**
 * Where a reader's files come from, as plain data that crosses to a worker (the model
 * loader, model-worker.ts, rebuilds the same reader there).
 */
export type FileSource = { kind: 'url'; base: string } | { kind: 'dropped'; files: File[] };

/** A SceneFileReader that can be rebuilt in a worker from its `source`. */
export interface PortableReader extends SceneFileReader {
  readonly source: FileSource;
}

/** The reader of a FileSource. */
export function readerOf(source: FileSource): PortableReader {
  return source.kind === 'url' ? urlSceneFiles(source.base) : droppedSceneFiles(source.files);
}

/** Files relative to `base` (the scene's URL, or the page's for a scene given inline). */
export function urlSceneFiles(base: string | URL): PortableReader {
  return {
    source: { kind: 'url', base: String(base) },
    async read(path: string, maxBytes: number): Promise<Uint8Array> {
      const url = urlInside(path, base);
      let response: Response;
      try {
        response = await fetch(url);
      } catch (e) {
        throw new Error(`cannot fetch ${url.href}: ${e instanceof Error ? e.message : String(e)}`);
      }
      if (!response.ok) throw new Error(`cannot fetch ${url.href}: HTTP ${response.status}`);
      const declared = Number(response.headers.get('content-length') ?? NaN);
      if (declared > maxBytes) {
        void response.body?.cancel();
        throw new Error(`the file has ${declared} bytes, more than the limit of ${maxBytes}`);
      }
      return readLimited(response, maxBytes);
    },
  };
}

/**
 * The URL of the file at `path` (a path, as in the scene format and as the core makes of
 * a model's URIs: core/gltf/io.ts) relative to `base`. Each segment is percent-encoded,
 * so `%2e%2e`, `\`, `?`, `#` and `:` stay parts of a name rather than becoming a parent,
 * a separator, a query or a scheme (WHATWG URL §4.4 reads `%2e%2e` as `..` and `\` as
 * `/`), and the URL must stay on the base's origin. Which folders a model may read is
 * the core's rule, checked before a path reaches here (docs/gltf.md, "Files a model may
 * read"): a model fetched by URL reads only files beside it. A scene's own `..` is
 * allowed here: the scene's origin holds nothing its page could not fetch anyway.
 */
export function urlInside(path: string, base: string | URL): URL {
  let folder: URL;
  let url: URL;
  try {
    folder = new URL('.', base);
    url = new URL(path.split('/').map(encodeURIComponent).join('/'), folder);
  } catch {
    throw new Error('it is not a valid URL');
  }
  if (url.origin !== folder.origin) {
    throw new Error(`it is not on the origin of ${folder.href}; files are read from there only`);
  }
  return url;
}

/** The body, at most `maxBytes` (read-bounded.ts, as the scene's own fetch is). */
async function readLimited(response: Response, maxBytes: number): Promise<Uint8Array> {
  try {
    return await readResponseBounded(response, maxBytes);
  } catch (e) {
    if (!(e instanceof ByteLimitError)) throw e;
    throw new Error(`the file has more than the limit of ${maxBytes} bytes`);
  }
}

/**
 * Files dropped (or picked) together with the scene. A scene's path matches a dropped
 * file by its relative path when the browser gives one (a dropped folder), else by its
 * last component, so `meshes/bunny.ply` finds a dropped `bunny.ply`.
 */
export function droppedSceneFiles(files: Iterable<File>): PortableReader {
  const list = Array.from(files);
  return {
    source: { kind: 'dropped', files: list },
    async read(path: string, maxBytes: number): Promise<Uint8Array> {
      const wanted = normalise(path);
      const name = wanted.slice(wanted.lastIndexOf('/') + 1);
      let matches = list.filter((f) => {
        const relative = normalise(f.webkitRelativePath || f.name);
        return relative === wanted || relative.endsWith('/' + wanted);
      });
      if (matches.length === 0) matches = list.filter((f) => f.name === name);
      if (matches.length === 0) {
        throw new Error(`it was not among the dropped files; drop the scene together with ${name}`);
      }
      if (matches.length > 1) {
        throw new Error(`${matches.length} dropped files are named ${name}; drop only one`);
      }
      const file = matches[0];
      if (file.size > maxBytes) {
        throw new Error(`the file has ${file.size} bytes, more than the limit of ${maxBytes}`);
      }
      return new Uint8Array(await file.arrayBuffer());
    },
  };
}

function normalise(path: string): string {
  return path
    .replace(/\\/g, '/')
    .split('/')
    .filter((part) => part !== '' && part !== '.')
    .join('/');
}
