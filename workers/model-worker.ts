/**
 * The model worker: loads one bare glTF model (core/gltf/bare-scene.ts) with the
 * browser's decoders (gltf-browser.ts), compiles it and packs it (pack.ts), and posts
 * both back, every array transferred (or shared), so the page only unpacks views. One
 * worker per load; the page terminates it when done or superseded.
 */
import {
  compileScene,
  countSkippedTriangles,
  loadBareModel,
  packScene,
  sceneWarnings,
  type LoadStage,
  type Scene,
} from '../src/core/index.ts';
import { browserTangentGenerator, decodeImageBrowser } from './gltf-browser.ts';
import type { ModelReply, ModelRequest } from './model-protocol.ts';
import { readerOf } from './scene-files.ts';

const post = (reply: ModelReply, transfer: Transferable[] = []) =>
  (self as unknown as Worker).postMessage(reply, transfer);

/**
 * The scene as the page keeps it: the model's arrays left out (`data: null`, as before
 * the file was read), so that they are not held twice — the packed scene has them. A
 * page that hands this scene back to setScene reads the file again; compileScene
 * refuses it rather than rendering nothing.
 */
function withoutModelData(scene: Scene): Scene {
  return {
    ...scene,
    shapes: scene.shapes.map((s) => (s.type === 'gltf' ? { ...s, data: null } : s)),
  };
}

self.onmessage = async (e: MessageEvent<ModelRequest>) => {
  const req = e.data;
  const onProgress = (stage: LoadStage, done: number, total: number) =>
    post({ type: 'progress', stage, done, total });
  try {
    const scene = await loadBareModel(req.bytes, req.name, readerOf(req.source), {
      decodeImage: decodeImageBrowser,
      // Without it, normal maps of primitives that have no tangents are ignored with a
      // warning (the loader says so) rather than failing the whole model.
      generateTangents: await browserTangentGenerator().catch(() => null),
      sharedTextures: req.shared,
      onProgress,
      width: req.width,
      height: req.height,
    });
    onProgress('compile', 0, 1);
    const packed = packScene(compileScene(scene), req.shared);
    onProgress('compile', 1, 1);
    const transfer: Transferable[] = [];
    if (packed.buffer instanceof ArrayBuffer) transfer.push(packed.buffer);
    post(
      {
        type: 'done',
        scene: withoutModelData(scene),
        packed,
        skippedTriangles: countSkippedTriangles(scene),
        warnings: sceneWarnings(scene),
      },
      transfer,
    );
  } catch (err) {
    post({ type: 'error', message: err instanceof Error ? err.message : String(err) });
  }
};
