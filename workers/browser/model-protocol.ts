/**
 * Messages between the page and the scene worker (model-worker.ts), which reads every
 * scene off the page's thread: a pathwise-scene/1 file (parse, validation, its mesh,
 * map and glTF files) or a bare glTF model (parse, texture decode, flattening,
 * tangents), then compiles and packs it (the BVH build), so that none of that blocks the
 * page however large or degenerate the scene.
 */
import type { BareModelChoices, LoadStage, PackedScene, Scene } from '../../src/core/index.ts';
import type { FileSource } from './scene-files.ts';

interface Common {
  /** Texels and the packed scene in SharedArrayBuffers (a cross-origin isolated page). */
  shared: boolean;
  /**
   * One Int32 the page sets to 1 to stop the load at its next check (isolated pages:
   * a busy worker is stopped by terminate() only after about 2 s in Chromium).
   */
  stop: SharedArrayBuffer | null;
}

/** A bare glTF model. */
export interface ModelRequest extends Common {
  kind: 'model';
  /** Where the files the model names are read from. */
  source: FileSource;
  /** The model file. */
  bytes: Uint8Array;
  /** Its name, for the scene, the shape and messages. */
  name: string;
  /** Image size whose aspect ratio the framing camera takes. */
  width: number;
  height: number;
  /** The user's choices for the model (bare-scene.ts), whole. */
  bare: BareModelChoices;
}

/** A pathwise-scene/1 scene: its bytes or text, or a scene object (validated there). */
export interface SceneRequest extends Common {
  kind: 'scene';
  /** Where the files the scene names are read from. */
  source: FileSource;
  input: Uint8Array | string | unknown;
  /** `input` is a Scene this page's loader made already (its arrays are trusted). */
  validated: boolean;
}

/**
 * A scene or a bare model at a URL, fetched in the worker (url-load.ts): a model when
 * its path names one or its bytes are a GLB, else a pathwise-scene/1 file; the files
 * either names are read beside it.
 */
export interface UrlRequest extends Common {
  kind: 'url';
  /** Absolute (the worker's own base is its script's, not the page's). */
  url: string;
  /** The URL as the caller wrote it, for messages. */
  label: string;
  /** Image size whose aspect ratio a model's framing camera takes. */
  width: number;
  height: number;
  /** The user's choices for a model (bare-scene.ts), whole. */
  bare: BareModelChoices;
}

export type LoadRequest = ModelRequest | SceneRequest | UrlRequest;

/**
 * Shapes per message of a large scene: a message is read on the page in one task, and
 * 100,000 shape objects in one took ~0.3–0.8 s there; 500 take about a millisecond (a
 * few times that on a loaded machine).
 */
export const SHAPES_PER_MESSAGE = 500;

export type ModelReply =
  /** The worker's script runs: the page sends its request now. */
  | { type: 'ready' }
  | { type: 'progress'; stage: LoadStage; done: number; total: number }
  /** The scene's shapes, in order, ahead of `done` (whose scene then has none). */
  | { type: 'shapes'; shapes: Scene['shapes'] }
  /**
   * The scene compiled and packed, and the scene itself (a model's arrays left out: its
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
