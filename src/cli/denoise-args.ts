/**
 * The options `--denoise` and `--raw FILE.pfm` of render and merge (the work is in
 * denoise-output.ts, loaded only when a command denoises).
 */
import { resolve } from 'node:path';
import { quote } from '../core/util/message.ts';
import { UsageError } from './errors.ts';

export interface DenoiseArgs {
  /** `--denoise`: `--out` is the denoised image. */
  denoise: boolean;
  /** `--raw FILE.pfm`: also the raw (noisy) mean radiance. */
  raw?: string;
}

export const DENOISE_USAGE = `  --denoise           write --out denoised by Open Image Denoise's network (with the first-hit
                      albedo and normal, which it records: implies --aux); biased, see
                      docs/denoise.md; not for a .film output
  --raw FILE.pfm      with --denoise: also write the raw (noisy) image`;

export const MERGE_DENOISE_USAGE = `  --denoise           write --out denoised (with albedo and normal when the parts carry them,
                      else from the colour alone); not for a .film output
  --raw FILE.pfm      with --denoise: also write the raw merged image`;

/** `--denoise` (a switch) and `--raw FILE.pfm` out of the split options; `out` is `--out`. */
export function parseDenoiseOptions(options: Map<string, string | true>, out: string): DenoiseArgs {
  const denoise = options.has('denoise');
  const raw = options.get('raw');
  if (raw === true) throw new UsageError('--raw needs a value');
  if (raw !== undefined && !denoise) throw new UsageError('--raw needs --denoise');
  if (raw !== undefined && !/\.pfm$/i.test(raw))
    throw new UsageError(`--raw must end in .pfm, got ${quote(raw, 240)}`);
  if (raw !== undefined && resolve(raw) === resolve(out))
    throw new UsageError(`--raw names the same file as --out: ${quote(raw, 240)}`);
  if (denoise && /\.film$/i.test(out))
    throw new UsageError(
      '--denoise writes an image, and a .film holds the exact sums: render the parts to .film, then denoise when merging (pathwise merge PARTS --denoise --out FILE.pfm)',
    );
  return { denoise, raw };
}
