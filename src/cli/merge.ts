/**
 * `pathwise merge PART.film… --out FILE.pfm|FILE.png|FILE.film`: adds the
 * exact sums of parts of one render. Integer addition is associative, so
 * the result is the same bits as one render of all the samples, in
 * whatever order the parts come and wherever the ranges were cut.
 *
 * Every part is checked whole before parts are compared (film-file.ts,
 * readFilmHeader: its checksum, then its pixels' counts against its header),
 * so a damaged part is named as damaged, not as a render of another scene.
 * Then the headers: parts of another scene or other settings, overlapping
 * ranges and disagreeing totals are refused with one sentence each, and
 * missing ranges are named (written anyway, with a warning, under
 * --allow-gaps). Pixels are then read one part at a time, so memory holds
 * two films at most.
 */
import { availableParallelism } from 'node:os';
import { basename } from 'node:path';
import { estimateNoise } from '../core/film/noise.ts';
import {
  findOverlap,
  formatRanges,
  missingRanges,
  normalizeRanges,
  rangeSamples,
  type SampleRange,
} from '../core/film/sample-ranges.ts';
import type { Film } from '../core/film/film.ts';
import { hasAux, type FilmHeader } from '../core/film/film-file.ts';
import { AuxOutputs } from './aux-output.ts';
import { MERGE_USAGE, parseMergeArgs, type MergeArgs } from './batch-args.ts';
import { encodeImage, encodeOutput } from './encode-output.ts';
import { denoiseWorkerUrl } from './render-command.ts';
import { CliError } from './errors.ts';
import { explainMismatch } from './film-compat.ts';
import { makeHeader, readFilmFile, readFilmHeader } from './film-file.ts';
import { OutputFile } from './output.ts';
import { testStage } from './test-stages.ts';
import { showPath } from './read-bounded.ts';

export async function merge(argv: string[]): Promise<void> {
  if (argv.includes('--help')) {
    process.stdout.write(MERGE_USAGE + '\n');
    return;
  }
  const args = parseMergeArgs(argv);
  testStage('read');
  const headers: FilmHeader[] = args.parts.map((p) => readFilmHeader(p));
  const first = headers[0];
  const name = (k: number) => showPath(basename(args.parts[k]));
  for (let k = 1; k < headers.length; k++) {
    const why = explainMismatch(name(0), first, name(k), headers[k]);
    if (why) throw new CliError(`cannot merge: ${why}`);
  }
  // Albedo and normal (pathwise-film/2) in every part or in none: a part without them
  // cannot give its samples' share of the aux means.
  const withAux = headers.findIndex((h) => hasAux(h));
  const withoutAux = headers.findIndex((h) => !hasAux(h));
  if (withAux >= 0 && withoutAux >= 0) {
    throw new CliError(
      `cannot merge: ${name(withAux)} holds albedo and normal (pathwise-film/2, rendered with --aux) and ${name(withoutAux)} does not (pathwise-film/1); render every part with --aux, or none`,
    );
  }
  const aux = withAux >= 0;
  if (args.aux.aux && !aux) {
    throw new CliError(
      `cannot write ${args.aux.albedo !== undefined ? '--albedo' : '--normal'}: the parts hold no albedo and normal (render them with --aux)`,
    );
  }
  const total = args.spp ?? first.spp;
  if (args.spp === undefined) {
    const other = headers.findIndex((h) => h.spp !== first.spp);
    if (other >= 0) {
      throw new CliError(
        `cannot merge: ${name(0)} is part of a ${first.spp}-spp render and ${name(other)} of a ${headers[other].spp}-spp one (give --spp N to choose the total)`,
      );
    }
  }
  let union: SampleRange[] = [];
  for (let k = 0; k < headers.length; k++) {
    for (const r of headers[k].ranges) {
      if (r[1] > total) {
        throw new CliError(
          `cannot merge: ${name(k)} holds samples ${formatRanges([r])}, beyond the total of ${total}`,
        );
      }
    }
    for (let j = 0; j < k; j++) {
      const both = findOverlap(headers[j].ranges, headers[k].ranges);
      if (both) {
        throw new CliError(
          `cannot merge: ${name(j)} and ${name(k)} both hold samples ${formatRanges([both])}`,
        );
      }
    }
    union = normalizeRanges([...union, ...headers[k].ranges])!;
  }
  const missing = missingRanges(union, total);
  const held = rangeSamples(union);
  if (missing.length > 0 && !args.allowGaps) {
    throw new CliError(
      `missing samples ${formatRanges(missing)}: the parts hold ${held} of ${total} samples per pixel (render the missing ranges, or give --allow-gaps to write the partial result)`,
    );
  }
  if (held === 0) throw new CliError('the parts hold no samples');

  // Ctrl-C or SIGTERM from here on removes the temporary file (temp-registry.ts).
  const output = await OutputFile.prepare(args.out);
  let auxOutputs: AuxOutputs | undefined;
  let raw: OutputFile | undefined;
  try {
    auxOutputs = await AuxOutputs.prepare(args.aux);
    raw = args.denoise.raw === undefined ? undefined : await OutputFile.prepare(args.denoise.raw);
    // Pixels, one part at a time.
    testStage('merge');
    const acc = readFilmFile(args.parts[0]);
    const stats = { ...acc.header.stats };
    for (let k = 1; k < args.parts.length; k++) {
      const part = readFilmFile(args.parts[k]);
      acc.film.add(part.film);
      stats.paths += part.header.stats.paths;
      stats.segments += part.header.stats.segments;
      stats.rejected += part.header.stats.rejected;
    }
    const header = makeHeader(first, total, union, stats, aux);
    testStage('write');
    if (args.denoise.denoise) {
      // Loaded only here: the network, its weights and its worker threads (docs/denoise.md).
      const { denoiseFilm } = await import('./denoise-output.ts');
      const denoised = await denoiseFilm(acc.film, availableParallelism(), denoiseWorkerUrl());
      if (denoised.inputs === 'colour')
        process.stderr.write(
          'pathwise: note: the parts carry no albedo and normal (rendered without --aux): denoised from the colour alone\n',
        );
      await raw?.commit(encodeOutput(args.denoise.raw!, acc.film, () => header, args.exposure));
      await output.commit(
        encodeImage(args.out, acc.film.width, acc.film.rows, denoised.image, args.exposure),
      );
    } else {
      await output.commit(encodeOutput(args.out, acc.film, () => header, args.exposure));
    }
    await auxOutputs.commit(acc.film);
    report(args, header, acc.film, missing, held, total);
  } finally {
    await output.discard();
    await auxOutputs?.discard();
    await raw?.discard();
  }
}

function report(
  args: MergeArgs,
  header: FilmHeader,
  film: Film,
  missing: SampleRange[],
  held: number,
  total: number,
): void {
  const stats = header.stats;
  const union = header.ranges;
  if (missing.length > 0) {
    process.stderr.write(
      `pathwise: warning: ${showPath(args.out)} lacks samples ${formatRanges(missing)}: it holds ${held} of ${total} samples per pixel\n`,
    );
  }
  if (args.json) {
    const noise = estimateNoise(film);
    process.stdout.write(
      JSON.stringify({
        parts: args.parts.length,
        width: header.settings.width,
        height: header.settings.height,
        spp: held,
        total,
        ranges: union,
        missing,
        noise: Number.isFinite(noise) ? noise : null,
        paths: stats.paths,
        segments: stats.segments,
        rejected_samples: stats.rejected,
      }) + '\n',
    );
  }
}
