/**
 * Scene requests: setScene and load read a scene (JSON, bytes, a File, a
 * URL, a bare glTF model), compile and pack it for the workers, and hand it
 * to the controller, which installs it and restarts.
 *
 * The last request always wins: each one bumps a counter, and a request
 * that is no longer the latest when its fetch or file read ends is dropped
 * (its fetch aborted, its model load stopped).
 */
import {
  bareChoices,
  type CompiledScene,
  compileScene,
  countSkippedTriangles,
  GLTF_FILE_BYTES,
  isGlbBytes,
  isModelFileName,
  isValidatedScene,
  LIMITS,
  loadBareModel,
  type LoadStage,
  markValidated,
  type PackedScene,
  packScene,
  parseScene,
  type ResolveOptions,
  resolveSceneFiles,
  type Scene,
  SceneError,
  type SceneFileReader,
  sceneNeedsFiles,
  sceneSizeProblem,
  sceneWarnings,
  validateScene,
} from '../core/index.ts';
import { ByteLimitError, readBlobBounded } from '../../workers/browser/read-bounded.ts';
import { fetchBounded, modelSizeProblem, readFetched } from '../../workers/browser/url-load.ts';
import { loadModelInWorker, type LoadedModel, type ModelJob } from './model-load.ts';
import { urlSceneFiles, type PortableReader } from '../../workers/browser/scene-files.ts';
import type { PathTracerOptions } from './types.ts';

/**
 * A scene ready to install; compiled and packed already when the model worker loaded it
 * (which also counted what the model's arrays, left out of `scene`, said).
 */
type Loaded = { scene: Scene } | LoadedModel;

/** What the requests need from the controller. */
export interface SceneHost {
  readonly canvas: HTMLCanvasElement;
  readonly options: PathTracerOptions;
  /** Whether the workers share memory (then scenes are packed into shared buffers). */
  shared(): boolean;
  /** Whether a scene is installed already (the first one may take options.bounces). */
  hasScene(): boolean;
  destroyed(): boolean;
  emit(type: string, detail: unknown): void;
  /**
   * Installs a packed scene and restarts; `load` and `warning` follow. `compiled`: the
   * compiled scene when the page made it (else the controller unpacks `packed` when it
   * needs one).
   */
  use(scene: Scene, packed: PackedScene, first: boolean, compiled: CompiledScene | null): void;
}

/** A model file's bytes, at most GLTF_FILE_BYTES (checked by its size before reading). */
async function readModelBlob(blob: Blob, name: string): Promise<Uint8Array> {
  if (blob.size > GLTF_FILE_BYTES) throw new Error(`${name}: ${modelSizeProblem(blob.size, true)}`);
  return new Uint8Array(await blob.arrayBuffer());
}

/** Scene text or bytes past this are read in the scene worker (~5 ms of parsing on the page). */
const LARGE_SCENE_BYTES = 256 * 1024;
/** Shapes, or triangles of loaded meshes, past which a scene object is read in the worker. */
const LARGE_SCENE_SHAPES = 2000;
const LARGE_SCENE_TRIANGLES = 50_000;

/** Whether reading and compiling `value` on the page could be a long task. */
function isLarge(value: unknown): boolean {
  if (typeof value === 'string' || value instanceof Uint8Array) {
    return value.length > LARGE_SCENE_BYTES;
  }
  const shapes = (value as { shapes?: unknown } | null)?.shapes;
  if (!Array.isArray(shapes)) return false;
  if (shapes.length > LARGE_SCENE_SHAPES) return true;
  let triangles = 0;
  for (const s of shapes) {
    const data = (s as { data?: { indices?: ArrayLike<number> } | null }).data;
    triangles += (data?.indices?.length ?? 0) / 3;
    if (Array.isArray((s as { indices?: unknown }).indices)) {
      triangles += (s as { indices: unknown[] }).indices.length / 3;
    }
  }
  return triangles > LARGE_SCENE_TRIANGLES;
}

/**
 * The buffer of bytes this page read itself, to transfer to the scene worker rather
 * than copy (none when the view covers only part of its buffer, or the value is text).
 */
function handOver(value: unknown): ArrayBuffer[] {
  if (!(value instanceof Uint8Array)) return [];
  const buffer = value.buffer;
  const whole = value.byteOffset === 0 && value.byteLength === buffer.byteLength;
  return whole && buffer instanceof ArrayBuffer ? [buffer] : [];
}

export class SceneRequests {
  private readonly host: SceneHost;
  /** The model worker's current load, stopped when a newer scene or destroy() comes. */
  private modelJob: ModelJob | null = null;
  /** Whether any scene was asked for (the one in the options then is not loaded). */
  requested = false;
  /**
   * Bumped by every scene request (setScene, load) and by destroy: a request
   * that is no longer the latest when its fetch or file read ends is
   * dropped, so the last request always wins.
   */
  private sceneRequest = 0;
  /** Aborts the fetch of a load that a newer request superseded. */
  private loadAbort: AbortController | null = null;

  constructor(host: SceneHost) {
    this.host = host;
  }

  /**
   * Loads a scene. A request superseded by a later one (setScene or load)
   * before it was read resolves without loading anything.
   */
  async setScene(value: unknown, files?: SceneFileReader): Promise<void> {
    const request = this.newSceneRequest();
    // Mesh, glTF and environment-map files: fetched relative to the page unless the
    // caller says how (a scene's URL, dropped files, a preset's assets).
    const reader = files ?? this.host.options.files ?? urlSceneFiles(document.baseURI);
    // The caller's bytes stay the caller's: copied to the scene worker, not handed over.
    return this.install(request, () => this.readScene(value, reader, false));
  }

  /** A new scene request: the older ones lose (a fetch in flight is aborted, a model load stopped). */
  newSceneRequest(): number {
    this.requested = true;
    this.loadAbort?.abort();
    this.loadAbort = null;
    this.modelJob?.cancel();
    return ++this.sceneRequest;
  }

  /** Stops the model worker's load, if one is running. */
  cancelModel(): void {
    this.modelJob?.cancel();
  }

  /**
   * Reads a scene: a File named `.glb` / `.gltf`, or bytes that are a GLB, is a bare
   * model (core/scene/load/bare-scene.ts), anything else a pathwise-scene/1 scene.
   */
  private async readScene(value: unknown, files: SceneFileReader, owned: boolean): Promise<Loaded> {
    if (value instanceof Blob) {
      const name = value instanceof File ? value.name : '';
      if (isModelFileName(name)) {
        return this.readModel(await readModelBlob(value, name), name, files, true);
      }
      // Bytes and files get the loader's byte bound and strict UTF-8, as on the command line.
      value = await readBlobBounded(value, LIMITS.fileBytes);
      owned = true;
    }
    if (value instanceof Uint8Array && isGlbBytes(value)) {
      return this.readModel(value, 'model.glb', files, owned);
    }
    // A large scene is parsed, validated, its files read and compiled in the scene
    // worker when those files can be read there (a URL, dropped files; the reader of a
    // scene without files is never asked), so the page keeps no long task of it. A small
    // one is read here (a millisecond or two, and no worker to start: the first picture
    // comes sooner, and a bundler that cannot find the worker's script is not asked to).
    const source = (files as Partial<PortableReader>).source;
    const portable = source !== undefined && typeof Worker !== 'undefined';
    if (portable && isLarge(value)) {
      const loaded = await this.inWorker(
        {
          kind: 'scene',
          input: value,
          validated: isValidatedScene(value),
          source,
          shared: this.host.shared(),
        },
        owned ? handOver(value) : [],
      );
      if (loaded !== null) return loaded;
    }
    const scene = isValidatedScene(value)
      ? value
      : typeof value === 'string' || value instanceof Uint8Array
        ? parseScene(value)
        : validateScene(value);
    if (!sceneNeedsFiles(scene)) return { scene };
    // Its files (meshes, maps, models: any size) are read and compiled in the worker.
    if (portable) {
      const loaded = await this.inWorker(
        { kind: 'scene', input: scene, validated: true, source, shared: this.host.shared() },
        [],
      );
      if (loaded !== null) return loaded;
    }
    // A scene file's glTF shapes load on the page (its reader may be any object).
    const hasGltf = scene.shapes.some((s) => s.type === 'gltf' && s.data === null);
    return {
      scene: await resolveSceneFiles(scene, files, hasGltf ? await this.gltfPlatform() : {}),
    };
  }

  /**
   * A bare model, framed at the aspect ratio of the picture it will be shown in: loaded,
   * compiled and packed in the model worker (model-load.ts) when its files can be read
   * there (a URL, dropped files), else on the page.
   */
  private async readModel(
    bytes: Uint8Array,
    name: string,
    files: SceneFileReader,
    owned: boolean,
  ): Promise<Loaded> {
    const { width, height } = this.framing();
    const source = (files as Partial<PortableReader>).source;
    if (source !== undefined && typeof Worker !== 'undefined') {
      const loaded = await this.inWorker(
        {
          kind: 'model',
          bytes,
          name,
          source,
          width,
          height,
          bare: bareChoices(this.host.options),
          shared: this.host.shared(),
        },
        owned ? handOver(bytes) : [],
      );
      if (loaded !== null) return loaded;
    }
    const scene = await loadBareModel(bytes, name, files, {
      ...(await this.gltfPlatform()),
      width,
      height,
      ...bareChoices(this.host.options),
    });
    return { scene };
  }

  /** The image size a bare model's framing camera takes the aspect ratio of. */
  private framing(): { width: number; height: number } {
    const { canvas, options } = this.host;
    // Only the aspect ratio matters here (the film follows the canvas).
    const clamp = (n: number) => Math.min(4096, Math.max(1, n));
    return {
      width: clamp(options.width ?? Math.round(canvas.clientWidth || 512)),
      height: clamp(options.height ?? Math.round(canvas.clientHeight || 512)),
    };
  }

  /** Loads in the scene worker (model-load.ts); null when it could not start. */
  private async inWorker(
    request: Parameters<typeof loadModelInWorker>[0],
    transfer: ArrayBuffer[],
  ): Promise<LoadedModel | null> {
    this.modelJob?.cancel();
    const job = loadModelInWorker(
      request,
      (stage, done, total) => this.progressLoad(stage, done, total),
      transfer,
    );
    this.modelJob = job;
    const loaded = await job.promise;
    if (loaded === null) return null;
    // The page's own loader made it (in the worker): handed back, it is trusted as is.
    markValidated(loaded.scene);
    return loaded;
  }

  /**
   * What loading glTF takes from the browser (gltf-browser.ts, imported only when a
   * model is loaded): createImageBitmap for images, MikkTSpace's WebAssembly, texels
   * in shared memory when the workers share it, and progress as `loadprogress` events.
   */
  private async gltfPlatform(): Promise<ResolveOptions> {
    const { browserGltfPlatform } = await import('../../workers/browser/gltf-browser.ts');
    return browserGltfPlatform(this.host.shared(), (stage, done, total) =>
      this.progressLoad(stage, done, total),
    );
  }

  private progressLoad(stage: LoadStage, done: number, total: number): void {
    this.host.emit('loadprogress', { stage, done, total });
  }

  /**
   * Installs the scene `read` gives, unless a later request came first; every failure
   * is an `error` event and a rejection with the loader's message.
   */
  private async install(request: number, read: () => Promise<Loaded>): Promise<void> {
    const host = this.host;
    let loaded: Loaded;
    try {
      loaded = await read();
    } catch (e) {
      // A superseded request's failure is nobody's concern any more.
      if (request !== this.sceneRequest) return;
      if (e instanceof ByteLimitError) e = new SceneError([sceneSizeProblem(e.size, e.exact)]);
      const message = e instanceof Error ? e.message : String(e);
      host.emit('error', { message });
      throw new Error(message);
    }
    // A later call started while this one read its files: that one wins.
    if (request !== this.sceneRequest || host.destroyed()) return;
    const { scene } = loaded;
    const packed = 'packed' in loaded ? loaded.packed : undefined;
    const first = !host.hasScene();
    const big =
      packed === undefined && scene.shapes.some((s) => s.type === 'gltf' || s.type === 'mesh');
    if (big) {
      // The BVH build is synchronous: let the page show the stage first.
      this.progressLoad('compile', 0, 1);
      await new Promise((resolve) => setTimeout(resolve, 0));
      if (request !== this.sceneRequest || host.destroyed()) return;
    }
    let compiled: CompiledScene | null = null;
    let packedScene: PackedScene;
    try {
      if (packed !== undefined) {
        // Compiled and packed by the scene worker: the controller makes views of it
        // when it needs them (click-to-focus).
        packedScene = packed;
      } else {
        compiled = compileScene(scene);
        if (big) this.progressLoad('compile', 1, 1);
        // Compiled once here (the picker uses it too) and shipped packed: the
        // workers neither parse nor compile nor build a BVH.
        packedScene = packScene(compiled, host.shared());
      }
    } catch (e) {
      if (!(e instanceof RangeError)) throw e;
      // Memory the scene's arrays (shared ones, when isolated) could not get.
      const message = `could not allocate memory for the compiled scene: ${e.message}`;
      host.emit('error', { message });
      throw new Error(message);
    }
    host.use(scene, packedScene, first, compiled);
    const warnings = 'warnings' in loaded ? loaded.warnings : sceneWarnings(scene);
    const skippedTriangles =
      'skippedTriangles' in loaded ? loaded.skippedTriangles : countSkippedTriangles(scene);
    host.emit('load', { scene, skippedTriangles, warnings });
    if (warnings.length > 0) host.emit('warning', { messages: warnings });
  }

  /**
   * Fetches and loads a scene or a bare model; superseded like setScene (its fetch is
   * aborted, or its worker stopped, then). The scene worker fetches and reads it, so
   * the page never holds the bytes; where that worker cannot start, the page does.
   */
  async load(url: string): Promise<void> {
    const request = this.newSceneRequest();
    return this.install(request, () => this.readUrl(url));
  }

  private async readUrl(url: string): Promise<Loaded> {
    let href = url;
    try {
      href = new URL(url, document.baseURI).href;
    } catch {
      // Not a URL: fetch says so.
    }
    const progress = (stage: LoadStage, done: number, total: number) =>
      this.progressLoad(stage, done, total);
    if (typeof Worker !== 'undefined') {
      const { width, height } = this.framing();
      const request = {
        kind: 'url',
        url: href,
        label: url,
        width,
        height,
        bare: bareChoices(this.host.options),
      } as const;
      const loaded = await this.inWorker({ ...request, shared: this.host.shared() }, []);
      if (loaded !== null) return loaded;
    }
    const abort = typeof AbortController !== 'undefined' ? new AbortController() : null;
    this.loadAbort = abort;
    const fetched = await fetchBounded(href, url, progress, abort?.signal);
    if (this.loadAbort === abort) this.loadAbort = null;
    return readFetched(
      fetched,
      (bytes, name, files) => this.readModel(bytes, name, files, true),
      (bytes, files) => this.readScene(bytes, files, true),
    );
  }
}
