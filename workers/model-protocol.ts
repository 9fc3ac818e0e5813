/**
 * Messages between the page and the model worker (model-worker.ts), which loads a bare
 * glTF model — parse, texture decode, flattening, tangents — and compiles and packs it
 * (the BVH build), so that none of that blocks the page.
 */
import type { LoadStage, PackedScene, Scene } from '../src/core/index.ts';
import type { FileSource } from './scene-files.ts';

export interface ModelRequest {
  /** The model file (transferred). */
  bytes: Uint8Array;
  /** Its name, for the scene, the shape and messages. */
  name: string;
  /** Where its buffers and images are read from. */
  source: FileSource;
  /** Image size whose aspect ratio the framing camera takes. */
  width: number;
  height: number;
  /** Texels and the packed scene in SharedArrayBuffers (a cross-origin isolated page). */
  shared: boolean;
}

export type ModelReply =
  | { type: 'progress'; stage: LoadStage; done: number; total: number }
  /**
   * The scene compiled and packed, and the scene itself without the model's arrays (its
   * shape's `data` null, as before its file was read: they live on in `packed`, and the
   * page need not hold them twice); the skipped-triangle count and warnings they gave.
   */
  | {
      type: 'done';
      scene: Scene;
      packed: PackedScene;
      skippedTriangles: number;
      warnings: string[];
    }
  | { type: 'error'; message: string };
