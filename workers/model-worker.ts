/**
 * The model worker: loads one bare glTF model (core/gltf/bare-scene.ts) with the
 * browser's decoders (gltf-browser.ts), compiles it and packs it (pack.ts), and posts
 * both back, every array transferred (or shared), so the page only unpacks views. One
 * worker per load; the page terminates it when done or superseded.
 */
import {
  compileScene,
  loadBareModel,
  packScene,
  type LoadStage,
  type Scene,
} from '../src/core/index.ts';
import { browserTangentGenerator, decodeImageBrowser } from './gltf-browser.ts';
import type { ModelReply, ModelRequest } from './model-protocol.ts';
import { readerOf } from './scene-files.ts';

const post = (reply: ModelReply, transfer: Transferable[] = []) =>
  (self as unknown as Worker).postMessage(reply, transfer);

/** Every ArrayBuffer (not shared memory) under the scene's shapes and environment map, once. */
function transferables(scene: Scene): ArrayBuffer[] {
  const found = new Set<ArrayBuffer>();
  const seen = new Set<object>();
  const walk = (v: unknown, depth: number): void => {
    if (v === null || typeof v !== 'object' || depth > 6 || seen.has(v)) return;
    seen.add(v);
    if (ArrayBuffer.isView(v)) {
      if (v.buffer instanceof ArrayBuffer) found.add(v.buffer);
      return;
    }
    for (const x of Object.values(v)) walk(x, depth + 1);
  };
  walk(scene.shapes, 0);
  walk(scene.environmentMap, 0);
  return [...found];
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
    const transfer: Transferable[] = transferables(scene);
    if (packed.buffer instanceof ArrayBuffer) transfer.push(packed.buffer);
    post({ type: 'done', scene, packed }, transfer);
  } catch (err) {
    post({ type: 'error', message: err instanceof Error ? err.message : String(err) });
  }
};
