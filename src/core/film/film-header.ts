/**
 * The header of a `.film` file (docs/film-format.md): its format names, its fields, the
 * errors of the format, and the validation of a parsed header (every field checked for
 * type and range, exact keys). film-file.ts reads and writes the whole file.
 */
import { LIMITS } from '../scene/format/types.ts';
import type { RenderSettings } from '../scene/format/render-settings.ts';
import { SAMPLER_KINDS, type SamplerKind } from '../sampling/sampler.ts';
import { FormatError } from '../io/format-error.ts';
import { MAX_COUNT, SCALE_BITS } from './exact-sum.ts';
import { normalizeRanges, rangeSamples, type SampleRange } from './sample-ranges.ts';

export const FILM_FORMAT = 'pathwise-film/1';
/**
 * Version 2: version 1 plus the denoising features (albedo and normal exact sums after
 * the `lo` plane, header key `aux`). Written only for films that carry them; a film
 * without them is still written as version 1, byte for byte as before.
 */
export const FILM_FORMAT_AUX = 'pathwise-film/2';
/** The aux channels a version-2 film holds, as its header names them. */
export const AUX_NAMES = ['albedo', 'normal'] as const;
/** Headers are small; this bounds what a lying length can make us read. */
export const MAX_HEADER_BYTES = 1 << 20;
const MAX_RANGES = 10_000;

/** One problem of a `.film` file: a FormatError naming the format, one printable line. */
export class FilmFileError extends FormatError {
  override name = 'FilmFileError';

  constructor(detail: string) {
    super(FILM_FORMAT, detail);
  }
}

/**
 * A problem with what the header says (not JSON, a field out of range, a key given
 * twice), as opposed to the file's length or magic: a reader that can check the
 * checksum first (src/cli/film-file.ts) reports a damaged file as damaged instead.
 */
export class FilmHeaderError extends FilmFileError {
  override name = 'FilmHeaderError';
}

/** Everything that changes a sample's value, besides the scene: the render settings. */
export type FilmSettings = RenderSettings;

export interface FilmHeader {
  format: typeof FILM_FORMAT | typeof FILM_FORMAT_AUX;
  /** Name and version of the renderer; parts of different renderers never merge. */
  renderer: string;
  /** SHA-256 (hex) of the scene as loaded, settings excluded (see docs/film-format.md). */
  scene_sha256: string;
  settings: FilmSettings;
  /** SHA-256 (hex) of renderer, scene_sha256 and settings: parts merge only with an equal key. */
  key: string;
  /** Fixed-point fraction bits of the exact sums (always 40 in this format). */
  scale_bits: number;
  /** The render's total: a complete film holds samples [0, spp). */
  spp: number;
  /** Sample ranges every pixel holds: sorted, disjoint, touching ranges joined. */
  ranges: SampleRange[];
  /** Paths traced (pixels × samples), path segments, and samples rejected as non-finite. */
  stats: { paths: number; segments: number; rejected: number };
  /** Version 2 only: the aux channels, always ["albedo", "normal"]. */
  aux?: typeof AUX_NAMES;
}

// --- header validation -----------------------------------------------------

const HEADER_KEYS = [
  'format',
  'renderer',
  'scene_sha256',
  'settings',
  'key',
  'scale_bits',
  'spp',
  'ranges',
  'stats',
] as const;
const SETTINGS_KEYS = ['width', 'height', 'maxBounces', 'seed', 'sampler', 'estimator'] as const;

function isObject(v: unknown): v is Record<string, unknown> {
  return typeof v === 'object' && v !== null && !Array.isArray(v);
}

function exactKeys(v: Record<string, unknown>, keys: readonly string[], where: string): void {
  for (const k of keys) if (!(k in v)) throw new FilmFileError(`header: ${where}${k} is missing`);
  for (const k of Object.keys(v)) {
    if (!keys.includes(k)) throw new FilmFileError(`header: unknown key ${where}${k}`);
  }
}

function integer(v: unknown, name: string, min: number, max: number): number {
  if (typeof v !== 'number' || !Number.isInteger(v) || v < min || v > max) {
    throw new FilmFileError(
      `header: ${name} must be an integer in [${min}, ${max}], got ${short(v)}`,
    );
  }
  return v;
}

function short(v: unknown): string {
  const s = JSON.stringify(v) ?? String(v);
  return s.length > 40 ? s.slice(0, 37) + '...' : s;
}

function sha256Hex(v: unknown, name: string): string {
  if (typeof v !== 'string' || !/^[0-9a-f]{64}$/.test(v)) {
    throw new FilmFileError(`header: ${name} must be 64 lowercase hex digits, got ${short(v)}`);
  }
  return v;
}

export function validateHeader(v: unknown, v2: boolean): FilmHeader {
  if (!isObject(v)) throw new FilmFileError('header: not a JSON object');
  exactKeys(v, v2 ? [...HEADER_KEYS, 'aux'] : HEADER_KEYS, '');
  const format = v2 ? FILM_FORMAT_AUX : FILM_FORMAT;
  if (v.format !== format) {
    throw new FilmFileError(
      `header: format must be "${format}" (as the file's first line says), got ${short(v.format)}`,
    );
  }
  if (v2 && JSON.stringify(v.aux) !== JSON.stringify(AUX_NAMES)) {
    throw new FilmFileError(
      `header: aux must be ${JSON.stringify(AUX_NAMES)}, got ${short(v.aux)}`,
    );
  }
  if (typeof v.renderer !== 'string' || v.renderer.length === 0 || v.renderer.length > 200) {
    throw new FilmFileError(
      `header: renderer must be a non-empty string, got ${short(v.renderer)}`,
    );
  }
  const s = v.settings;
  if (!isObject(s)) throw new FilmFileError('header: settings must be an object');
  exactKeys(s, 'adaptive' in s ? [...SETTINGS_KEYS, 'adaptive'] : SETTINGS_KEYS, 'settings.');
  if ('adaptive' in s && s.adaptive !== true) {
    throw new FilmFileError(
      `header: settings.adaptive must be true where present (a uniform render leaves it out), got ${short(s.adaptive)}`,
    );
  }
  const width = integer(s.width, 'settings.width', 1, LIMITS.pixels);
  const height = integer(s.height, 'settings.height', 1, LIMITS.pixels);
  if (width * height > LIMITS.pixels) {
    throw new FilmFileError(
      `header: settings.width * settings.height must be at most ${LIMITS.pixels} pixels, got ${width * height}`,
    );
  }
  const settings: FilmSettings = {
    width,
    height,
    maxBounces: integer(s.maxBounces, 'settings.maxBounces', 0, LIMITS.maxBounces),
    seed: integer(s.seed, 'settings.seed', 0, 2 ** 32 - 1),
    sampler: s.sampler as SamplerKind,
    estimator: s.estimator as FilmSettings['estimator'],
    ...(s.adaptive === true ? { adaptive: true } : {}),
  };
  if (!SAMPLER_KINDS.includes(settings.sampler)) {
    throw new FilmFileError(
      `header: settings.sampler must be one of ${SAMPLER_KINDS.join(', ')}, got ${short(s.sampler)}`,
    );
  }
  if (settings.estimator !== 'nee-mis' && settings.estimator !== 'bsdf') {
    throw new FilmFileError(
      `header: settings.estimator must be nee-mis or bsdf, got ${short(s.estimator)}`,
    );
  }
  if (v.scale_bits !== SCALE_BITS) {
    throw new FilmFileError(`header: scale_bits must be ${SCALE_BITS}, got ${short(v.scale_bits)}`);
  }
  const spp = integer(v.spp, 'spp', 1, LIMITS.spp);
  const ranges = validateRanges(v.ranges, spp);
  const st = v.stats;
  if (!isObject(st)) throw new FilmFileError('header: stats must be an object');
  exactKeys(st, ['paths', 'segments', 'rejected'], 'stats.');
  const paths = integer(st.paths, 'stats.paths', 0, Number.MAX_SAFE_INTEGER);
  const rejected = integer(st.rejected, 'stats.rejected', 0, Number.MAX_SAFE_INTEGER);
  return {
    format,
    renderer: v.renderer,
    scene_sha256: sha256Hex(v.scene_sha256, 'scene_sha256'),
    settings,
    key: sha256Hex(v.key, 'key'),
    scale_bits: SCALE_BITS,
    spp,
    ranges,
    stats: {
      paths,
      segments: integer(st.segments, 'stats.segments', 0, Number.MAX_SAFE_INTEGER),
      rejected,
    },
    ...(v2 ? { aux: AUX_NAMES } : {}),
  };
}

function validateRanges(v: unknown, spp: number): SampleRange[] {
  if (!Array.isArray(v) || v.length > MAX_RANGES) {
    throw new FilmFileError(
      `header: ranges must be an array of at most ${MAX_RANGES} [start, end] pairs`,
    );
  }
  const ranges: SampleRange[] = v.map((r, k) => {
    if (!Array.isArray(r) || r.length !== 2) {
      throw new FilmFileError(`header: ranges[${k}] must be a [start, end] pair, got ${short(r)}`);
    }
    const a = integer(r[0], `ranges[${k}][0]`, 0, spp - 1);
    const b = integer(r[1], `ranges[${k}][1]`, a + 1, spp);
    return [a, b];
  });
  const canonical = normalizeRanges(ranges);
  if (canonical === null || JSON.stringify(canonical) !== JSON.stringify(ranges)) {
    throw new FilmFileError(
      `header: ranges must be sorted, disjoint and not touching, got ${short(v)}`,
    );
  }
  if (rangeSamples(ranges) > MAX_COUNT) {
    throw new FilmFileError(`header: ranges hold more than ${MAX_COUNT} samples`);
  }
  return ranges;
}
