/**
 * The scene worker: reads one scene off the page's thread — a pathwise-scene/1 file
 * (parse, validation, its mesh, map and glTF files) or a bare glTF model
 * (core/scene/load/bare-scene.ts) with the browser's decoders (gltf-browser.ts) — compiles it
 * and packs it (pack.ts), and posts both back, every array transferred (or shared), so
 * the page only installs views: no task of a load runs on the page, however large or
 * degenerate the scene. One worker per load; the page stops it when done or superseded
 * (the stop word first, checked in the long loops of loading and the BVH build, then
 * terminate()).
 */
import {
  CancelledError,
  compileScene,
  countSkippedTriangles,
  loadBareModel,
  markValidated,
  packScene,
  parseScene,
  resolveSceneFiles,
  sceneNeedsFiles,
  sceneWarnings,
  setCancelCheck,
  validateScene,
  type LoadStage,
  type ResolveOptions,
  type Scene,
  type SceneFileReader,
} from '../../src/core/index.ts';
import { browserGltfPlatform } from './gltf-browser.ts';
import {
  SHAPES_PER_MESSAGE,
  type LoadRequest,
  type ModelReply,
  type ModelRequest,
  type UrlRequest,
} from './model-protocol.ts';
import { readerOf } from './scene-files.ts';
import { fetchBounded, readFetched } from './url-load.ts';

const post = (reply: ModelReply, transfer: Transferable[] = []) =>
  (self as unknown as Worker).postMessage(reply, transfer);

/**
 * The scene as the page keeps it: a model's arrays left out (`data: null`, as before
 * the file was read), so that they are not held twice — the packed scene has them. A
 * page that hands this scene back to setScene reads the file again; compileScene
 * refuses it rather than rendering nothing. Mesh and map arrays stay (transferred), so
 * a scene handed back needs no file.
 */
function forThePage(scene: Scene, transfer: Transferable[]): Scene {
  const own = (a: ArrayBufferView | null) => {
    if (a !== null && a.buffer instanceof ArrayBuffer && !transfer.includes(a.buffer)) {
      transfer.push(a.buffer);
    }
  };
  for (const s of scene.shapes) {
    if (s.type === 'mesh' && s.data !== null) {
      own(s.data.positions);
      own(s.data.indices);
      own(s.data.normals);
    }
  }
  own(scene.environmentMap?.image?.rgb ?? null);
  return {
    ...scene,
    shapes: scene.shapes.map((s) => (s.type === 'gltf' ? { ...s, data: null } : s)),
  };
}

function platform(req: LoadRequest, onProgress: ResolveOptions['onProgress']) {
  return browserGltfPlatform(req.shared, onProgress);
}

async function read(req: LoadRequest, onProgress: ResolveOptions['onProgress']): Promise<Scene> {
  if (req.kind === 'url') return readUrl(req, onProgress!);
  const files = readerOf(req.source);
  if (req.kind === 'model') return readModel(req, req.bytes, req.name, files, onProgress);
  const input = req.input;
  const scene = req.validated
    ? markValidated(input as Scene)
    : typeof input === 'string' || input instanceof Uint8Array
      ? parseScene(input)
      : validateScene(input);
  return withFiles(req, scene, files, onProgress);
}

/** A scene's mesh, map and glTF files, read beside it. */
async function withFiles(
  req: LoadRequest,
  scene: Scene,
  files: SceneFileReader,
  onProgress: ResolveOptions['onProgress'],
): Promise<Scene> {
  if (!sceneNeedsFiles(scene)) return scene;
  const gltf = scene.shapes.some((s) => s.type === 'gltf' && s.data === null);
  return resolveSceneFiles(scene, files, gltf ? await platform(req, onProgress) : { onProgress });
}

async function readModel(
  req: ModelRequest | UrlRequest,
  bytes: Uint8Array,
  name: string,
  files: SceneFileReader,
  onProgress: ResolveOptions['onProgress'],
): Promise<Scene> {
  return loadBareModel(bytes, name, files, {
    ...(await platform(req, onProgress)),
    width: req.width,
    height: req.height,
    ...req.bare,
  });
}

/** A URL's scene or model (as the page's load() reads it when this worker cannot start). */
async function readUrl(
  req: UrlRequest,
  onProgress: NonNullable<ResolveOptions['onProgress']>,
): Promise<Scene> {
  return readFetched(
    await fetchBounded(req.url, req.label, onProgress),
    (bytes, name, files) => readModel(req, bytes, name, files, onProgress),
    (bytes, files) => withFiles(req, parseScene(bytes), files, onProgress),
  );
}

self.onmessage = async (e: MessageEvent<LoadRequest>) => {
  const req = e.data;
  if (req.stop !== null) {
    const stop = new Int32Array(req.stop);
    setCancelCheck(() => {
      if (Atomics.load(stop, 0) !== 0) throw new CancelledError();
    });
  }
  const onProgress = (stage: LoadStage, done: number, total: number) =>
    post({ type: 'progress', stage, done, total });
  try {
    const scene = await read(req, onProgress);
    onProgress('compile', 0, 1);
    const packed = packScene(compileScene(scene), req.shared);
    onProgress('compile', 1, 1);
    const transfer: Transferable[] = [];
    if (packed.buffer instanceof ArrayBuffer) transfer.push(packed.buffer);
    const skippedTriangles = countSkippedTriangles(scene);
    const warnings = sceneWarnings(scene);
    let page = forThePage(scene, transfer);
    if (page.shapes.length > SHAPES_PER_MESSAGE) {
      for (let i = 0; i < page.shapes.length; i += SHAPES_PER_MESSAGE) {
        post({ type: 'shapes', shapes: page.shapes.slice(i, i + SHAPES_PER_MESSAGE) });
      }
      page = { ...page, shapes: [] };
    }
    post({ type: 'done', scene: page, packed, skippedTriangles, warnings }, transfer);
  } catch (err) {
    post({ type: 'error', message: err instanceof Error ? err.message : String(err) });
  }
};

// The page sends its request only once this arrives: it then hands over (transfers)
// bytes it owns, which it keeps while a worker that never starts could still make it
// load on the page instead.
post({ type: 'ready' });
