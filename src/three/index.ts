/**
 * pathwise/three: three.js scenes into pathwise. `three` is a peer dependency that this
 * entry never imports at run time (three-shapes.ts says why).
 */
export { cameraFromThree, fromThree, readerOf, THREE_MODEL_FILE } from './from-three.ts';
export type { FromThreeOptions, ThreeConversion, ThreeSceneDocument } from './from-three.ts';
