/**
 * The batch options of `pathwise render` (sample ranges, stop criteria,
 * checkpoints) and the arguments of `pathwise merge`. Every problem is a
 * UsageError with a one-line message (exit status 2).
 */
import { MERGE_DENOISE_USAGE, parseDenoiseOptions, type DenoiseArgs } from './denoise-args.ts';
import { LIMITS } from '../core/scene/format/types.ts';
import { quote, sanitize } from '../core/util/message.ts';
import { UsageError } from './errors.ts';
import { MERGE_AUX_USAGE, parseAuxOptions, type AuxArgs } from './aux-output.ts';
import {
  POSITIVE_DECIMAL,
  parseDecimalValue,
  parseIntegerValue,
  switchWithoutValue,
} from './values.ts';

export interface BatchOptions {
  /** --samples A:B: render only samples [A, B) of every pixel. */
  samples?: [number, number];
  /** --time SECONDS: whole-process wall-time budget. */
  time?: number;
  /** --noise REL: stop once the estimated relative noise is at most REL. */
  noise?: number;
  /** --checkpoint FILE.film: where to write the film every --checkpoint-every seconds. */
  checkpoint?: string;
  checkpointEvery: number;
  /** --resume FILE.film: continue from this checkpoint (a missing file starts afresh). */
  resume?: string;
  /** --pilot FILE.film: an adaptive part's pilot, read instead of rendered (adaptive.ts). */
  pilot?: string;
}

export const BATCH_OPTION_NAMES = [
  'samples',
  'time',
  'noise',
  'checkpoint',
  'checkpoint-every',
  'resume',
  'pilot',
] as const;

export const BATCH_USAGE = `  --samples A:B       render only samples [A, B) of every pixel (a part of an --spp N render; 0 <= A < B <= N)
  --time SECONDS      stop at the end of the last whole pass that fits in this whole-process wall time
  --noise REL         stop once the estimated relative noise of the image is at most REL (e.g. 0.01)
                      (with --time or --noise and no --spp, the render may go up to 1048576 spp)
  --checkpoint FILE.film  write the film there every --checkpoint-every seconds (atomically)
  --checkpoint-every S    seconds between checkpoints (default 60)
  --resume FILE.film  continue from a checkpoint of the same render (a missing FILE starts from the beginning)
  --pilot FILE.film   an adaptive part that does not start at sample 0 reads the sample map's pilot from
                      FILE (the same render's --samples 0:16) instead of rendering those 16 passes again`;

export const MERGE_USAGE = `usage: pathwise merge PART.film... --out FILE.pfm|FILE.png|FILE.film [options]
  merges parts of one render (given in any order) into the image of all their samples
  --spp N             the render's total (default: the parts' own, which must agree)
  --allow-gaps        write the partial result when sample ranges are missing
  --exposure E        PNG exposure multiplier (default 1)
  --json              print one JSON line describing the result on stdout
${MERGE_AUX_USAGE}
${MERGE_DENOISE_USAGE}`;

/** Runs a values.ts parser, turning its CliError into a UsageError. */
function usage<T>(parse: () => T): T {
  try {
    return parse();
  } catch (e) {
    throw new UsageError((e as Error).message);
  }
}

function positiveNumber(name: string, text: string): number {
  return usage(() => parseDecimalValue(`--${name}`, text, POSITIVE_DECIMAL));
}

function filmPath(name: string, value: string): string {
  if (!/\.film$/i.test(value)) {
    throw new UsageError(`--${name} must end in .film, got ${quote(value, 240)}`);
  }
  return value;
}

/** Parses the batch options out of the already split `--name value` map. */
export function parseBatchOptions(options: Map<string, string | true>): BatchOptions {
  const text = (name: string): string | undefined => {
    const v = options.get(name);
    return typeof v === 'string' ? v : undefined;
  };
  const out: BatchOptions = { checkpointEvery: 60 };
  const samples = text('samples');
  if (samples !== undefined) {
    const m = /^([0-9]{1,16}):([0-9]{1,16})$/.exec(samples);
    const a = m ? Number(m[1]) : NaN;
    const b = m ? Number(m[2]) : NaN;
    if (!m || !Number.isSafeInteger(a) || !Number.isSafeInteger(b) || a >= b) {
      throw new UsageError(`--samples must be A:B with integers 0 <= A < B, got ${quote(samples)}`);
    }
    out.samples = [a, b];
  }
  const time = text('time');
  if (time !== undefined) out.time = positiveNumber('time', time);
  const noise = text('noise');
  if (noise !== undefined) out.noise = positiveNumber('noise', noise);
  const every = text('checkpoint-every');
  if (every !== undefined) out.checkpointEvery = positiveNumber('checkpoint-every', every);
  const checkpoint = text('checkpoint');
  if (checkpoint !== undefined) out.checkpoint = filmPath('checkpoint', checkpoint);
  const resume = text('resume');
  if (resume !== undefined) out.resume = filmPath('resume', resume);
  const pilot = text('pilot');
  if (pilot !== undefined) out.pilot = filmPath('pilot', pilot);
  if (every !== undefined && checkpoint === undefined) {
    throw new UsageError('--checkpoint-every needs --checkpoint FILE.film');
  }
  return out;
}

export interface MergeArgs {
  parts: string[];
  out: string;
  spp?: number;
  allowGaps: boolean;
  exposure: number;
  json: boolean;
  /** `--albedo`, `--normal`: the merged denoising features (the parts must carry them). */
  aux: AuxArgs;
  /** `--denoise`, `--raw`: the merged image denoised (denoise-output.ts). */
  denoise: DenoiseArgs;
}

export function parseMergeArgs(argv: string[]): MergeArgs {
  const parts: string[] = [];
  const options = new Map<string, string | true>();
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (!a.startsWith('--')) {
      parts.push(a);
      continue;
    }
    const eq = a.indexOf('=');
    const name = eq >= 0 ? a.slice(2, eq) : a.slice(2);
    if (options.has(name)) throw new UsageError(`--${sanitize(name)} is given twice`);
    if (name === 'json' || name === 'allow-gaps' || name === 'help' || name === 'denoise') {
      if (eq >= 0) usage(() => switchWithoutValue(`--${name}`, a));
      options.set(name, true);
      continue;
    }
    if (!['out', 'spp', 'exposure', 'albedo', 'normal', 'raw'].includes(name)) {
      throw new UsageError(`unknown option --${sanitize(name)} (try: pathwise merge --help)`);
    }
    const value = eq >= 0 ? a.slice(eq + 1) : argv[++i];
    if (value === undefined) throw new UsageError(`--${sanitize(name)} needs a value`);
    options.set(name, value);
  }
  if (parts.length === 0) throw new UsageError('merge needs at least one PART.film');
  for (const p of parts) {
    if (!/\.film$/i.test(p))
      throw new UsageError(`parts must be .film files, got ${quote(p, 240)}`);
  }
  const out = options.get('out');
  if (typeof out !== 'string') throw new UsageError('missing --out FILE.pfm|FILE.png|FILE.film');
  if (!/\.(pfm|png|film)$/i.test(out)) {
    throw new UsageError(`--out must end in .pfm, .png or .film, got ${quote(out, 240)}`);
  }
  let spp: number | undefined;
  const sppText = options.get('spp');
  if (typeof sppText === 'string') {
    spp = usage(() => parseIntegerValue('--spp', sppText, 1, LIMITS.spp));
  }
  let exposure = 1;
  const exposureText = options.get('exposure');
  if (typeof exposureText === 'string') exposure = positiveNumber('exposure', exposureText);
  return {
    parts,
    out,
    spp,
    allowGaps: options.has('allow-gaps'),
    exposure,
    json: options.has('json'),
    aux: parseAuxOptions(options, out),
    denoise: parseDenoiseOptions(options, out),
  };
}
