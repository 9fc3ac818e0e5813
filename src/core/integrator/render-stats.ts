/**
 * Counters a render adds to. A module of its own so that code that only
 * counts (the command line's main thread) does not import the tracer:
 * path-tracer.ts sets the hot loop on PathTracer's prototype, a side effect
 * a bundler must keep, which would pull the whole tracer into its bundle.
 */

/** Counters a render adds to; `segments` counts every ray traced (camera, bounce, shadow). */
export class RenderStats {
  paths = 0;
  segments = 0;
  rejected = 0;
}
