/**
 * The path tracer: a scene, a camera, a sampler and the scratch records of
 * the hot loop, and the loops over pixels and samples that feed a film. One
 * path is traced by `trace` (trace-path.ts), which holds the estimators.
 */
import { BsdfQuery, BsdfSample, BsdfValue } from '../bsdf/records.ts';
import { Camera } from '../camera/camera.ts';
import type { Film } from '../film/film.ts';
import { Hit, Ray } from '../geometry/ray.ts';
import { intersectScene } from '../accel/trace.ts';
import { EnvironmentSample } from '../lights/environment-map.ts';
import { LightSample } from '../lights/lights.ts';
import { LIGHT_SPLIT, type LightBvh } from '../lights/light-bvh.ts';
import { TriangleSurface } from './triangle-surface.ts';
import { GltfWork } from './gltf-surface.ts';
import { DIM_PER_BOUNCE, DEFAULT_SAMPLER, Sampler } from '../sampling/sampler.ts';
import type { CompiledScene } from '../scene/compile/compile.ts';
import type { CameraDesc } from '../scene/format/types.ts';
import type { Estimator, RenderSettings } from '../scene/format/render-settings.ts';
import { RenderStats } from './render-stats.ts';
import { NEE_RECORD, trace } from './trace-path.ts';
import { AuxSample, traceAux } from './aux.ts';
import { ADAPTIVE_PILOT, adaptiveCount } from '../film/adaptive.ts';

export { RenderStats };

export type { Estimator, RenderSettings };

/**
 * What a tracer is built from: the render settings (seed 0, NEE with MIS and the
 * default sampler where left out) and the camera. A job that extends RenderSettings is
 * passed as it is.
 */
export type TracerOptions = Pick<RenderSettings, 'width' | 'height' | 'maxBounces'> &
  Partial<RenderSettings> & {
    camera: CameraDesc;
    /**
     * How next-event estimation chooses its lights: by the light BVH with splitting
     * (the default, and what every render uses), by the light BVH one light at a time,
     * or by power alone; the last two are kept to measure against (bench/many-lights.ts)
     * and for the validation that compares them.
     */
    lightSampler?: LightSamplerKind;
  };

/**
 * Light choice of next-event estimation (see TracerOptions.lightSampler): 'split', up
 * to LIGHT_SPLIT lights per vertex through the light BVH (light-bvh.ts chooseSplit);
 * 'bvh', one through it; 'power', one by power.
 */
export type LightSamplerKind = 'split' | 'bvh' | 'power';

export class PathTracer {
  readonly scene: CompiledScene;
  readonly camera: Camera;
  readonly width: number;
  readonly height: number;
  maxBounces: number;
  readonly estimator: Estimator;
  readonly sampler: Sampler;
  /** The scene's light BVH, or null where lights are chosen by power (trace-path.ts). */
  readonly lightBvh: LightBvh | null;
  /** The most lights next-event estimation samples at a vertex through the light BVH. */
  readonly lightSplit: number;
  /** Radiance of the last traced path. */
  lr = 0;
  lg = 0;
  lb = 0;
  // Scratch records of trace (trace-path.ts), created once: the hot loop
  // allocates nothing. Not for other callers.
  readonly ray = new Ray();
  readonly shadowRay = new Ray();
  readonly hit = new Hit();
  readonly bs = new BsdfSample();
  readonly fv = new BsdfValue();
  readonly ls = new LightSample();
  /** Splitting's light samples waiting for their shadow rays (NEE_RECORD numbers each). */
  readonly neeRecords = new Float64Array(LIGHT_SPLIT * NEE_RECORD);
  readonly es = new EnvironmentSample();
  readonly ts = new TriangleSurface();
  /** This bounce's random numbers (see Sampler.fill). */
  readonly bq = new BsdfQuery();
  readonly u = new Float64Array(DIM_PER_BOUNCE);
  /** glTF scratch (gltf-surface.ts) and the number deciding alpha pass-through. */
  readonly gw = new GltfWork();
  readonly au = new Float64Array(1);
  /** The albedo and normal of the last sample, for films with aux planes (aux.ts). */
  readonly auxSample = new AuxSample();
  /**
   * An adaptive render's per-pixel rates (film/adaptive.ts), row-major over the
   * image, or null: every pixel takes every pass.
   */
  sampleMap: Uint8Array | null = null;

  constructor(scene: CompiledScene, options: TracerOptions) {
    this.scene = scene;
    this.width = options.width;
    this.height = options.height;
    this.maxBounces = options.maxBounces;
    this.estimator = options.estimator ?? 'nee-mis';
    this.lightBvh = options.lightSampler === 'power' ? null : scene.lightBvh();
    this.lightSplit = options.lightSampler === 'bvh' ? 1 : LIGHT_SPLIT;
    this.sampler = new Sampler(options.seed ?? 0, options.sampler ?? DEFAULT_SAMPLER);
    this.camera = new Camera(options.camera, options.width, options.height);
  }

  setCamera(desc: CameraDesc): void {
    this.camera.set(desc);
  }

  /** Adds samples [sampleStart, sampleEnd) of every pixel of rows [y0, y1) to the film. */
  renderRows(
    film: Film,
    y0: number,
    y1: number,
    sampleStart: number,
    sampleEnd: number,
    stats: RenderStats,
  ): void {
    if (this.sampleMap !== null) {
      for (let y = y0; y < y1; y++)
        this.renderRowAdaptive(film, y, sampleStart, sampleEnd, this.sampleMap, stats);
      return;
    }
    // A film with aux planes takes its own row loop: renderRow, the loop of every other
    // render, stays the code V8 was measured with.
    if (film.auxHi !== null) {
      for (let y = y0; y < y1; y++) this.renderRowAux(film, y, sampleStart, sampleEnd, stats);
      return;
    }
    for (let y = y0; y < y1; y++) this.renderRow(film, y, sampleStart, sampleEnd, stats);
  }

  /**
   * renderRow for a film with aux planes: each sample's radiance, then its first-hit
   * albedo and normal (aux.ts) from the same camera ray and random numbers, added
   * together or rejected together.
   */
  renderRowAux(
    film: Film,
    y: number,
    sampleStart: number,
    sampleEnd: number,
    stats: RenderStats,
  ): void {
    const width = this.width;
    const a = this.auxSample;
    for (let x = 0; x < width; x++) {
      for (let s = sampleStart; s < sampleEnd; s++) {
        this.trace(x, y, s, stats);
        // The sampler is still at this sample: traceAux skips its set-up.
        this.traceAux(x, y, s, a, true);
        if (!film.addSampleAux(x, y, this, a)) stats.rejected++;
      }
    }
  }

  /**
   * renderRow of an adaptive render: passes [passStart, passEnd) add each pixel's
   * sample indices [count(passStart), count(passEnd)) at its rate in `map`
   * (film/adaptive.ts), with albedo and normal where the film has them.
   */
  renderRowAdaptive(
    film: Film,
    y: number,
    passStart: number,
    passEnd: number,
    map: Uint8Array,
    stats: RenderStats,
  ): void {
    const width = this.width;
    const a = this.auxSample;
    const aux = film.auxHi !== null;
    for (let x = 0; x < width; x++) {
      const k = map[y * width + x];
      const s1 = adaptiveCount(passEnd, ADAPTIVE_PILOT, k);
      for (let s = adaptiveCount(passStart, ADAPTIVE_PILOT, k); s < s1; s++) {
        this.trace(x, y, s, stats);
        if (aux) {
          this.traceAux(x, y, s, a, true);
          if (!film.addSampleAux(x, y, this, a)) stats.rejected++;
        } else if (!film.addRadiance(x, y, this)) stats.rejected++;
      }
    }
  }

  /**
   * Adds samples [sampleStart, sampleEnd) of every pixel of row y. The
   * film's sums are exact (film/exact-sum.ts), so the result is the same
   * bits whichever worker renders the row and however the samples are
   * split into calls.
   */
  renderRow(
    film: Film,
    y: number,
    sampleStart: number,
    sampleEnd: number,
    stats: RenderStats,
  ): void {
    const width = this.width;
    // The samples of one pixel one after another: their camera rays start
    // alike (branches and cache lines of the first intersection repeat), and
    // the film's exact sums make the order irrelevant to the bits.
    for (let x = 0; x < width; x++) {
      for (let s = sampleStart; s < sampleEnd; s++) {
        this.trace(x, y, s, stats);
        if (!film.addRadiance(x, y, this)) stats.rejected++;
      }
    }
  }

  /**
   * Traces sample `sampleIndex` of pixel (px, py); the radiance lands in
   * lr, lg, lb. The hot loop, in trace-path.ts (set on the prototype below).
   */
  declare trace: (px: number, py: number, sampleIndex: number, stats: RenderStats) => void;

  /** The albedo and normal of sample `sampleIndex` of pixel (px, py) into `out` (aux.ts). */
  declare traceAux: (
    px: number,
    py: number,
    sampleIndex: number,
    out: AuxSample,
    started?: boolean,
  ) => void;

  /**
   * Distance along the camera's forward axis to the surface seen through
   * film point (filmX, filmY), or NaN where the ray escapes — what
   * click-to-focus sets as the focus distance.
   */
  pick(filmX: number, filmY: number): number {
    const cam = this.camera;
    const aperture = cam.aperture;
    cam.aperture = 0;
    cam.generateRay(filmX, filmY, 0.5, 0.5, this.ray);
    cam.aperture = aperture;
    if (!intersectScene(this.scene, this.ray, this.hit)) return NaN;
    const r = this.ray;
    return this.hit.t * (r.dx * cam.fx + r.dy * cam.fy + r.dz * cam.fz);
  }
}

PathTracer.prototype.trace = trace;
PathTracer.prototype.traceAux = traceAux;
