/**
 * `--albedo FILE.pfm`, `--normal FILE.pfm` and `--aux` (render and merge): the
 * denoising features of integrator/aux.ts, written as PFM images (the mean over the
 * same accepted samples as the radiance), and carried in `.film` parts as
 * `pathwise-film/2` (docs/film-format.md) so that split renders merge them exactly.
 */
import { resolve } from 'node:path';
import { encodePfm } from '../core/io/pfm.ts';
import type { Film } from '../core/film/film.ts';
import { quote } from '../core/util/message.ts';
import { UsageError } from './errors.ts';
import { OutputFile } from './output.ts';

export interface AuxArgs {
  /** `--albedo FILE.pfm`: the mean first-hit albedo. */
  albedo?: string;
  /** `--normal FILE.pfm`: the mean first-hit shading normal (world space). */
  normal?: string;
  /** Whether the render records albedo and normal (`--aux`, or either file asked for). */
  aux: boolean;
}

/** The options' names: `aux` is a switch, the others take a file. */
export const AUX_OPTION_NAMES = ['albedo', 'normal', 'aux'] as const;

export const AUX_USAGE = `  --albedo FILE.pfm   also write the first-hit albedo (Open Image Denoise's albedo feature image)
  --normal FILE.pfm   also write the first-hit shading normal (world space, in [-1, 1])
  --aux               record albedo and normal in a .film output (pathwise-film/2) without
                      writing them (implied by --albedo and --normal)`;

export const MERGE_AUX_USAGE = `  --albedo FILE.pfm   also write the merged albedo (the parts must carry it: rendered with --aux)
  --normal FILE.pfm   also write the merged shading normal`;

/**
 * The aux options out of the already split `--name value` map; `out` is the main output,
 * which neither image may overwrite.
 */
export function parseAuxOptions(options: Map<string, string | true>, out: string): AuxArgs {
  const file = (name: string): string | undefined => {
    const v = options.get(name);
    if (typeof v !== 'string') return undefined;
    if (!/\.pfm$/i.test(v))
      throw new UsageError(`--${name} must end in .pfm, got ${quote(v, 240)}`);
    return v;
  };
  const albedo = file('albedo');
  const normal = file('normal');
  for (const [name, path] of [
    ['albedo', albedo],
    ['normal', normal],
  ] as const) {
    if (path !== undefined && resolve(path) === resolve(out)) {
      throw new UsageError(`--${name} names the same file as --out: ${quote(path, 240)}`);
    }
  }
  if (albedo !== undefined && normal !== undefined && resolve(albedo) === resolve(normal)) {
    throw new UsageError(`--albedo and --normal name the same file: ${quote(albedo, 240)}`);
  }
  return {
    albedo,
    normal,
    aux: options.has('aux') || albedo !== undefined || normal !== undefined,
  };
}

/** The aux images' outputs, checked (their temporary files created) before the work starts. */
export class AuxOutputs {
  private constructor(
    private readonly albedo: OutputFile | undefined,
    private readonly normal: OutputFile | undefined,
  ) {}

  static async prepare(args: AuxArgs): Promise<AuxOutputs> {
    const albedo = args.albedo ? await OutputFile.prepare(args.albedo) : undefined;
    try {
      const normal = args.normal ? await OutputFile.prepare(args.normal) : undefined;
      return new AuxOutputs(albedo, normal);
    } catch (e) {
      await albedo?.discard();
      throw e;
    }
  }

  /** Writes the images asked for from the film's aux planes. */
  async commit(film: Film): Promise<void> {
    if (this.albedo) await this.albedo.commit(encodePfm(film.width, film.rows, film.auxMean(0)));
    if (this.normal) await this.normal.commit(encodePfm(film.width, film.rows, film.auxMean(3)));
  }

  async discard(): Promise<void> {
    await this.albedo?.discard();
    await this.normal?.discard();
  }
}
