/**
 * `npm run fuzz`: the spec fuzzer's campaign (scripts/fuzz.mjs bundles and starts this).
 *
 *   FUZZ_SEED=1 FUZZ_CASES=3000 npm run fuzz [-- --jobs N --failures DIR (default dist/fuzz/failures) --json FILE]
 *   npm run fuzz -- --replay DIR      re-runs the cases saved under DIR
 *   npm run fuzz -- --case 1:473,1:418 [--save DIR]   runs (and saves) single cases
 *
 * Exit status 1 when any case failed, 0 otherwise.
 */
import { availableParallelism } from 'node:os';
import { writeFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { isFailure } from './classify.ts';
import {
  baselines,
  judge,
  listing,
  loadSaved,
  runCampaign,
  table,
  type CampaignOptions,
} from './campaign.ts';
import { makeCase } from './cases.ts';
import { runCase, writeCase } from './runner.ts';

function flag(argv: string[], name: string): string | undefined {
  const i = argv.indexOf(name);
  return i >= 0 ? argv[i + 1] : undefined;
}

async function main(argv: string[]): Promise<number> {
  const bin = resolve(flag(argv, '--bin') ?? process.env.SPECFUZZ_BIN ?? 'bin/pathwise.js');
  const options: CampaignOptions = {
    bin,
    probe: process.env.SPECFUZZ_PROBE,
    seed: Number(process.env.FUZZ_SEED ?? flag(argv, '--seed') ?? 1),
    cases: Number(process.env.FUZZ_CASES ?? flag(argv, '--cases') ?? 2000),
    jobs: Number(flag(argv, '--jobs') ?? availableParallelism()),
    baselineRuns: 3,
    slowSeconds: 2,
    heavyMiB: 512,
    timeoutMs: Number(flag(argv, '--timeout') ?? 60) * 1000,
    rssCapMiB: Number(flag(argv, '--rss-cap') ?? 3072),
    failDir: resolve(flag(argv, '--failures') ?? 'dist/fuzz/failures'),
    log: (line) => process.stderr.write(`${line}\n`),
  };
  const replay = flag(argv, '--replay');
  const single = flag(argv, '--case');
  if (replay || single) {
    let failed = 0;
    const save = flag(argv, '--save');
    const cases = replay
      ? loadSaved(resolve(replay))
      : single!.split(',').map((id) => {
          const [seed, index] = id.split(':').map(Number);
          return makeCase(seed, index);
        });
    // One valid run per format, so that a replayed case is judged slow or heavy as in a campaign.
    const base = await baselines({ ...options, baselineRuns: 1 });
    for (const c of cases) {
      if (save) writeCase(resolve(save, `${c.format}-${c.seed}-${c.index}`), c);
      const r = judge(await runCase(c, options), base[c.format], options);
      if (isFailure(r.outcome)) failed++;
      process.stdout.write(
        `${r.outcome.padEnd(16)} ${r.seconds.toFixed(2)} s ${r.rssMiB.toFixed(0)} MiB  case ${r.id} ${r.format} [${r.variant}] ${r.mutation}\n  ${r.stderr.trim().split('\n').join('\n  ') || '(no message)'}\n`,
      );
    }
    return failed > 0 ? 1 : 0;
  }
  const start = performance.now();
  process.stderr.write(
    `spec fuzz: seed ${options.seed}, ${options.cases} cases, ${options.jobs} at a time, failures to ${options.failDir}\n`,
  );
  const rep = await runCampaign(options);
  process.stdout.write(`\n${table(rep)}\n`);
  if (rep.failures.length > 0)
    process.stdout.write(`\n${rep.failures.length} failing cases:\n${listing(rep.failures)}\n`);
  process.stdout.write(`\n${((performance.now() - start) / 1000).toFixed(0)} s wall\n`);
  const json = flag(argv, '--json');
  if (json) writeFileSync(json, JSON.stringify(rep, null, 1));
  return rep.failures.length > 0 ? 1 : 0;
}

process.exitCode = await main(process.argv.slice(2));
