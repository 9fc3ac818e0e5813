/**
 * The three.js side of <pathwise-view>: the element's `threeScene` and `threeCamera`.
 * The scene is converted by fromThree (pathwise/three, loaded only when a page sets a
 * three.js scene, so the widget costs nothing more otherwise) and its files handed to the
 * tracer as dropped files, which the scene worker reads off the page's thread. The camera
 * is followed every animation frame: when its matrix, field of view, zoom or lens
 * change, accumulation restarts from the new view (the geometry stays loaded). A change
 * to the geometry or materials is the caller's to announce (`threeChanged()`), since
 * three.js has no change events to watch.
 */
import type { CameraDesc } from '../core/index.ts';
import { droppedSceneFiles } from '../../workers/browser/scene-files.ts';

type ThreeBridge = typeof import('../three/index.ts');
let bridge: Promise<ThreeBridge> | null = null;
function loadBridge(): Promise<ThreeBridge> {
  return (bridge ??= import('../three/index.ts'));
}

/** What the link needs of the tracer (PathTracerController). */
export interface LinkedTracer {
  setScene(value: unknown, files?: ReturnType<typeof droppedSceneFiles>): Promise<void>;
  setCamera(camera: CameraDesc): void;
}

export class ThreeLink {
  scene: object | null = null;
  camera: object | null = null;
  private watching = 0;
  private lastKey = '';
  private convert: ThreeBridge['cameraFromThree'] | null = null;
  /** Bumped by every load: a conversion that a newer one overtook does not load. */
  private generation = 0;

  get active(): boolean {
    return this.scene !== null && this.camera !== null;
  }

  /** Converts the scene and loads it; the conversion's warnings go to `warn`. */
  async load(tracer: LinkedTracer, warn: (messages: string[]) => void): Promise<void> {
    const generation = ++this.generation;
    const three = await loadBridge();
    this.convert = three.cameraFromThree;
    const converted = await three.fromThree(this.scene!, this.camera!);
    if (generation !== this.generation) return;
    if (converted.warnings.length > 0) warn(converted.warnings);
    const files = [...converted.files].map(
      ([name, bytes]) => new File([bytes as Uint8Array<ArrayBuffer>], name),
    );
    this.lastKey = this.cameraKey();
    await tracer.setScene(converted.scene, droppedSceneFiles(files));
  }

  /** Follows the camera until stop(); `tracer` is asked for on every frame. */
  watch(tracer: () => LinkedTracer | null): void {
    this.unwatch();
    const step = () => {
      this.watching = requestAnimationFrame(step);
      const t = tracer();
      if (t === null || this.camera === null || this.convert === null) return;
      const key = this.cameraKey();
      if (key === this.lastKey) return;
      this.lastKey = key;
      t.setCamera(this.convert(this.camera));
    };
    this.watching = requestAnimationFrame(step);
  }

  /** Stops following the camera and drops a conversion still running. */
  stop(): void {
    this.generation++;
    this.unwatch();
  }

  private unwatch(): void {
    if (this.watching !== 0) cancelAnimationFrame(this.watching);
    this.watching = 0;
  }

  /** Everything of the camera the view depends on, as one string. */
  private cameraKey(): string {
    const c = this.camera as Record<string, unknown> & {
      updateWorldMatrix?(a: boolean, b: boolean): void;
      matrixWorld?: { elements: ArrayLike<number> };
    };
    if (!c?.matrixWorld) return '';
    // Controls move the camera's position and quaternion; its matrix follows only on a
    // render, which three's renderer no longer does while pathwise shows the view.
    c.updateWorldMatrix?.(true, false);
    return [
      Array.from(c.matrixWorld.elements).join(','),
      c.fov,
      c.zoom,
      c.fStop,
      c.bokehSize,
      c.focusDistance,
    ].join('/');
  }
}
