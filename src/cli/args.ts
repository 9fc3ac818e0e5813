/**
 * Command-line parsing for `pathwise render`. Every problem is a
 * UsageError with a one-line message; the caller exits with status 2.
 */
import { DEFAULT_SAMPLER, SAMPLER_KINDS, type SamplerKind } from '../core/sampling/sampler.ts';
import type { Estimator } from '../core/integrator/path-tracer.ts';
import { quote, sanitize } from '../core/util/message.ts';
import {
  BATCH_OPTION_NAMES,
  BATCH_USAGE,
  parseBatchOptions,
  type BatchOptions,
} from './batch-args.ts';
import { UsageError } from './errors.ts';
import { DENOISE_USAGE, parseDenoiseOptions, type DenoiseArgs } from './denoise-args.ts';
import { AUX_OPTION_NAMES, AUX_USAGE, parseAuxOptions, type AuxArgs } from './aux-output.ts';
import { BARE_ENVIRONMENTS, type BareEnvironment } from '../core/lights/studio.ts';
import type { BareModelChoices } from '../core/scene/load/bare-scene.ts';
import {
  POSITIVE_DECIMAL,
  parseDecimalValue,
  parseIntegerValue,
  switchWithoutValue,
} from './values.ts';

export interface RenderArgs {
  scenePath: string;
  out: string;
  spp?: number;
  width?: number;
  height?: number;
  bounces?: number;
  seed: number;
  threads?: number;
  exposure: number;
  estimator: Estimator;
  sampler: SamplerKind;
  /** `--adaptive on|off`: adaptive sampling (core/film/adaptive.ts); on by default with --noise. */
  adaptive: boolean;
  json: boolean;
  stripeRows?: number;
  batch: BatchOptions;
  /** `--allow-read DIR`, repeatable: folders beyond the scene's whose files may be read. */
  allowRead: string[];
  /** `--environment studio|none`, `--variant NAME`: a bare model's choices (core/scene/load/bare-scene.ts). */
  bare: BareModelChoices;
  /** `--albedo`, `--normal`, `--aux`: the denoising features (aux-output.ts). */
  aux: AuxArgs;
  /** `--denoise`, `--raw`: the denoised output (denoise-output.ts). */
  denoise: DenoiseArgs;
}

export const USAGE = `usage: pathwise render SCENE.json --out FILE.pfm|FILE.png|FILE.film [options]
       pathwise merge PART.film... --out FILE.pfm|FILE.png|FILE.film (see pathwise merge --help)
  SCENE.json          a scene file, or - (or /dev/stdin) for standard input; at most 16 MiB
                      or a glTF model (MODEL.glb, MODEL.gltf): framed by its bounds (or its
                      first camera) in a studio environment
  --spp N             samples per pixel (default: the scene's settings.spp)
  --width W --height H  image size (default: the scene's settings)
  --bounces B         maximum scattering events per path (default: settings.maxBounces)
  --seed S            random seed, an integer in [0, 2^32) (default 0)
  --threads T         worker threads (default: available cores)
  --exposure E        PNG exposure multiplier (default 1)
  --estimator nee-mis|bsdf  next-event estimation with MIS (default) or BSDF sampling only
  --sampler sobol|independent  random numbers: Owen-scrambled Sobol for the leading dimensions (default), or the independent PCG hash
  --adaptive on|off   adaptive sampling: after 16 uniform passes each pixel takes later passes
                      at a rate set by its neighbours' noise (unbiased; default: on with
                      --noise, off otherwise)
  --stripe-rows R     rows per work stripe (default: automatic; the image does not depend on it)
  --json              print one JSON line of statistics on stdout (a switch: no value)
  --environment studio|none  a glTF model's environment: the studio (default), or none
                      to see only the model's own lights (not for scene files)
  --variant NAME      a glTF model's material variant (KHR_materials_variants), by name
                      (default: its default materials; not for scene files)
  --allow-read DIR    files may also be read from DIR (repeatable); by default a scene and its
                      models read only files inside the scene's folder (a bare model's folder)
${AUX_USAGE}
${DENOISE_USAGE}
${BATCH_USAGE}`;

/** The first line of USAGE, printed alone (on stderr) when no command is given. */
export const SYNOPSIS = USAGE.split('\n')[0];

/** Options that are switches: present or absent, never with a value. */
const SWITCHES = new Set(['json', 'help', 'aux', 'denoise']);

const INTEGER_OPTIONS = new Set([
  'spp',
  'width',
  'height',
  'bounces',
  'seed',
  'threads',
  'stripe-rows',
]);

function parseInteger(name: string, text: string, min: number, max: number): number {
  try {
    return parseIntegerValue(`--${name}`, text, min, max);
  } catch (e) {
    throw new UsageError((e as Error).message);
  }
}

export function parseRenderArgs(argv: string[]): RenderArgs {
  const positional: string[] = [];
  const options = new Map<string, string | true>();
  const allowRead: string[] = [];
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (!a.startsWith('--')) {
      positional.push(a);
      continue;
    }
    const eq = a.indexOf('=');
    const name = eq >= 0 ? a.slice(2, eq) : a.slice(2);
    if (name === 'allow-read') {
      // Repeatable: each names one more folder (docs/gltf.md, "Files a model may read").
      const dir = eq >= 0 ? a.slice(eq + 1) : argv[++i];
      if (dir === undefined || dir === '') throw new UsageError('--allow-read needs a folder');
      allowRead.push(dir);
      continue;
    }
    if (options.has(name)) throw new UsageError(`--${sanitize(name)} is given twice`);
    if (SWITCHES.has(name)) {
      if (eq >= 0) {
        try {
          switchWithoutValue(`--${name}`, a);
        } catch (e) {
          throw new UsageError((e as Error).message);
        }
      }
      options.set(name, true);
      continue;
    }
    const value = eq >= 0 ? a.slice(eq + 1) : argv[++i];
    if (value === undefined) throw new UsageError(`--${sanitize(name)} needs a value`);
    options.set(name, value);
  }
  const known = new Set([
    ...INTEGER_OPTIONS,
    'out',
    'exposure',
    'estimator',
    'sampler',
    'adaptive',
    'environment',
    'variant',
    'json',
    'help',
    ...AUX_OPTION_NAMES,
    'denoise',
    'raw',
    ...BATCH_OPTION_NAMES,
  ]);
  for (const name of options.keys()) {
    if (!known.has(name)) throw new UsageError(`unknown option --${sanitize(name)}`);
  }
  if (positional.length !== 1) {
    throw new UsageError(
      positional.length === 0
        ? 'missing the scene file'
        : `expected one scene file, got ${positional.length}: ` +
            positional.map((p) => quote(p)).join(' '),
    );
  }
  const out = options.get('out');
  if (typeof out !== 'string') throw new UsageError('missing --out FILE.pfm|FILE.png|FILE.film');
  if (!/\.(pfm|png|film)$/i.test(out))
    throw new UsageError(`--out must end in .pfm, .png or .film, got ${quote(out, 240)}`);
  const int = (name: string, min: number, max: number): number | undefined => {
    const v = options.get(name);
    return typeof v === 'string' ? parseInteger(name, v, min, max) : undefined;
  };
  const exposureText = options.get('exposure');
  let exposure = 1;
  if (typeof exposureText === 'string') {
    try {
      exposure = parseDecimalValue('--exposure', exposureText, POSITIVE_DECIMAL);
    } catch (e) {
      throw new UsageError((e as Error).message);
    }
  }
  const estimator = options.get('estimator') ?? 'nee-mis';
  if (estimator !== 'nee-mis' && estimator !== 'bsdf') {
    throw new UsageError(`--estimator must be nee-mis or bsdf, got ${quote(String(estimator))}`);
  }
  const sampler = options.get('sampler') ?? DEFAULT_SAMPLER;
  if (!SAMPLER_KINDS.includes(sampler as SamplerKind)) {
    throw new UsageError(
      `--sampler must be one of ${SAMPLER_KINDS.join(', ')}, got ${quote(String(sampler))}`,
    );
  }
  const adaptiveText = options.get('adaptive');
  if (adaptiveText !== undefined && adaptiveText !== 'on' && adaptiveText !== 'off') {
    throw new UsageError(`--adaptive must be on or off, got ${quote(String(adaptiveText))}`);
  }
  const batch = parseBatchOptions(options);
  const adaptive = adaptiveText === undefined ? batch.noise !== undefined : adaptiveText === 'on';
  if (batch.pilot !== undefined && !adaptive) {
    throw new UsageError('--pilot is for adaptive sampling: add --adaptive on (or --noise)');
  }
  const environment = options.get('environment');
  if (environment !== undefined && !BARE_ENVIRONMENTS.includes(environment as BareEnvironment)) {
    throw new UsageError(
      `--environment must be one of ${BARE_ENVIRONMENTS.join(', ')}, got ${quote(String(environment))}`,
    );
  }
  const aux = parseAuxOptions(options, out);
  const denoise = parseDenoiseOptions(options, out);
  // The network takes the first-hit albedo and normal: a denoised render records them.
  if (denoise.denoise) aux.aux = true;
  return {
    scenePath: positional[0],
    out,
    // Range checks of spp/size/bounces against the scene limits happen in
    // validateSettingsOverride, with the same messages as the loader.
    spp: int('spp', -Number.MAX_SAFE_INTEGER, Number.MAX_SAFE_INTEGER),
    width: int('width', -Number.MAX_SAFE_INTEGER, Number.MAX_SAFE_INTEGER),
    height: int('height', -Number.MAX_SAFE_INTEGER, Number.MAX_SAFE_INTEGER),
    bounces: int('bounces', -Number.MAX_SAFE_INTEGER, Number.MAX_SAFE_INTEGER),
    seed: int('seed', 0, 2 ** 32 - 1) ?? 0,
    threads: int('threads', 1, 256),
    exposure,
    estimator,
    sampler: sampler as SamplerKind,
    adaptive,
    json: options.has('json'),
    stripeRows: int('stripe-rows', 1, 1 << 24),
    batch,
    allowRead,
    bare: {
      environment: environment as BareEnvironment | undefined,
      variant: options.get('variant') as string | undefined,
    },
    aux,
    denoise,
  };
}
