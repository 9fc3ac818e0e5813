/**
 * The stripe scheme shared by the Node command line and the browser pool:
 * the image is cut into horizontal stripes of `stripeRows` rows, and
 * workers claim stripes from a shared atomic counter. Because every pixel's
 * samples depend only on (seed, pixel, sample) and the film's sums are
 * exact (independent of order and grouping), the result is bit-identical
 * for any stripe height, any number of workers and any split of the
 * samples.
 */
import type { CameraDesc, CompiledScene } from '../../src/core/index.ts';
import { PathTracer } from '../../src/core/integrator/path-tracer.ts';
import type { RenderSettings } from '../../src/core/scene/format/render-settings.ts';

/** A render's settings, camera and stripes; the scene itself travels packed (core/scene/compile/pack.ts). */
export interface StripeJob extends RenderSettings {
  camera: CameraDesc;
  stripeRows: number;
  /** The film carries albedo and normal planes (integrator/aux.ts). */
  aux?: boolean;
}

/** Builds the tracer for a job over an already compiled scene (each worker does this once). */
export function createTracer(job: StripeJob, scene: CompiledScene): PathTracer {
  return new PathTracer(scene, job);
}
