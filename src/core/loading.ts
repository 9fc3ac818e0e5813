/**
 * The loading entry: reading a scene's files (meshes, environment maps, glTF models with
 * their textures and tangents) and bare glTF models. Heavier than the tracer's entry
 * (glTF-Transform, the PNG and JPEG decoders): the command line imports it only when a
 * scene names files; index.ts is both entries together.
 */
export {
  loadScene,
  resolveSceneFiles,
  type LoadStage,
  type ResolveOptions,
  type SceneFileReader,
} from './scene/load/load.ts';
export type {
  DracoDecoderModule,
  GltfDecoders,
  MeshoptDecoderLike,
} from './scene/format/gltf-model.ts';
export {
  bareChoices,
  bareModelScene,
  isGlbBytes,
  loadBareModel,
  type BareModelChoices,
  type BareSceneOptions,
} from './scene/load/bare-scene.ts';
