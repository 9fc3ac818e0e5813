/**
 * pathwise core: the DOM-free tracer. Runs in Node, in Web Workers and on
 * the main thread alike.
 */
export * from './scene/format/types.ts';
export {
  RENDER_SETTING_KEYS,
  renderSettingsOf,
  type RenderSettings,
} from './scene/format/render-settings.ts';
export {
  parseScene,
  validateScene,
  validateSettingsOverride,
  isValidatedScene,
  markValidated,
  SceneError,
} from './scene/validate/validate.ts';
export { setCancelCheck, CancelledError } from './util/cancel.ts';
export {
  loadScene,
  resolveSceneFiles,
  sceneNeedsFiles,
  type LoadStage,
  type ResolveOptions,
  type SceneFileReader,
} from './scene/load/load.ts';
export {
  bareModelScene,
  isGlbBytes,
  isModelFileName,
  loadBareModel,
  type BareSceneOptions,
} from './scene/load/bare-scene.ts';
export { studioEnvironment, STUDIO_FILE } from './lights/studio.ts';
export { sceneWarnings } from './scene/validate/warnings.ts';
export { countSkippedTriangles } from './scene/validate/mesh-desc.ts';
export {
  compileScene,
  CompiledScene,
  BVH_THRESHOLD,
  type CompileOptions,
  type SceneData,
} from './scene/compile/compile.ts';
export { packScene, unpackScene, canShareMemory, type PackedScene } from './scene/compile/pack.ts';
export {
  PathTracer,
  RenderStats,
  type Estimator,
  type TracerOptions,
} from './integrator/path-tracer.ts';
export { Film } from './film/film.ts';
export { Camera } from './camera/camera.ts';
export { encodePfm, decodePfm, type PfmImage, type PfmDecodeOptions } from './io/pfm.ts';
export { encodeHdr, decodeHdr } from './io/hdr.ts';
export { FormatError } from './io/format-error.ts';
export { encodePng, zlibStored } from './io/png.ts';
export { acesFilmic, srgbEncode, toDisplayByte, tonemapSums } from './io/tonemap.ts';
export { pcgHash } from './rng/pcg.ts';
export { Sampler, SAMPLER_KINDS, DEFAULT_SAMPLER, type SamplerKind } from './sampling/sampler.ts';
export { estimateNoise, type NoiseInput } from './film/noise.ts';
export {
  FILM_FORMAT,
  FilmFileError,
  MAX_HEADER_BYTES,
  decodeFilmFile,
  decodeFilmHeader,
  encodeFilmFile,
  filmFileLength,
  type FilmFile,
  type FilmHeader,
  type FilmSettings,
} from './film/film-file.ts';
export { SCALE_BITS, SAMPLE_LIMIT, exactValue } from './film/exact-sum.ts';
export {
  findOverlap,
  formatRanges,
  missingRanges,
  normalizeRanges,
  rangeSamples,
  type SampleRange,
} from './film/sample-ranges.ts';
export { crc32 } from './io/crc32.ts';
export { quote, sanitize, printableLine } from './util/message.ts';
export { sceneSizeProblem } from './scene/validate/validate.ts';
export { GLTF_FILE_BYTES, type GltfLoadOptions } from './gltf/load.ts';
export type { TangentGenerator } from './scene/format/gltf-model.ts';
export { createMikkTSpace } from './gltf/mikktspace-wasm.ts';
export { decodeImageJs } from './texture/decode-js.ts';
export type { DecodedImage } from './texture/decoded-image.ts';
