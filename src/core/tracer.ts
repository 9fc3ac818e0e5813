/**
 * The tracer's entry: the scene format and its rules, compiling and packing, the path
 * tracer, the film and the image formats — everything a render needs once a scene is in
 * memory, and nothing that reads a scene's files (meshes, maps, glTF models and their
 * image decoders: loading.ts). Importing it loads no reader, so the command line's start
 * and a render worker stay small; index.ts is both entries together.
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
export { GLTF_FILE_BYTES, isModelFileName } from './gltf/file-names.ts';
export {
  BARE_ENVIRONMENTS,
  studioEnvironment,
  STUDIO_FILE,
  type BareEnvironment,
} from './lights/studio.ts';
export { sceneWarnings } from './scene/validate/warnings.ts';
export { sceneNeedsFiles } from './scene/validate/needs-files.ts';
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
  type LightSamplerKind,
  type TracerOptions,
} from './integrator/path-tracer.ts';
export { AUX_CHANNELS, Film, type AuxValues } from './film/film.ts';
export { AuxSample, gltfAlbedo } from './integrator/aux.ts';
export { Camera } from './camera/camera.ts';
export { encodePfm, decodePfm, type PfmImage, type PfmDecodeOptions } from './io/pfm.ts';
export { encodeHdr, decodeHdr } from './io/hdr.ts';
export { FormatError } from './io/format-error.ts';
export { encodePng, zlibStored } from './io/png.ts';
export { acesFilmic, srgbEncode, toDisplayByte, tonemapSums } from './io/tonemap.ts';
export { pcgHash } from './rng/pcg.ts';
export { Sampler, SAMPLER_KINDS, DEFAULT_SAMPLER, type SamplerKind } from './sampling/sampler.ts';
export { estimateNoise, type NoiseInput } from './film/noise.ts';
export { ADAPTIVE_PILOT, RATE_ONE, adaptiveCount, buildSampleMap } from './film/adaptive.ts';
export { emptyImageMessage, filmIsEmpty } from './integrator/empty-image.ts';
export {
  FILM_FORMAT,
  FILM_FORMAT_AUX,
  hasAux,
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
