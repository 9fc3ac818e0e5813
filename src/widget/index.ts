/**
 * pathwise for the browser, without side effects: the JS API
 * (`createPathTracer`) and the <pathwise-view> element class, which is
 * registered only when `definePathwiseView()` is called. The package's main
 * entry (register.ts) is this plus the registration.
 */
export {
  createPathTracer,
  droppedSceneFiles,
  mappedSceneFiles,
  urlSceneFiles,
} from '../view/index.ts';
export type {
  ComputeMode,
  DisplayMode,
  FallbackInfo,
  PathTracerController,
  PathTracerEventMap,
  PathTracerOptions,
  ProgressInfo,
  RenderStatsInfo,
} from '../view/types.ts';
export type { CameraDesc, Scene, SceneFileReader, Vec3 } from '../core/index.ts';
export { PathwiseViewElement, type PathwiseViewEventMap } from './element.ts';
export { definePathwiseView } from './define.ts';
export { moduleWorkerFactory } from '../view/worker-source.ts';
