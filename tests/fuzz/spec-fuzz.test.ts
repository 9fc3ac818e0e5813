/**
 * The format fuzzer of issue 27 (tests/fuzz/spec) at a small fixed budget: eight cases of
 * every format, seed 27, each through the real command line in a child process. Every case
 * must end as a finite image, one clear line, or notes, within 10 s more than a valid file of
 * its format (the campaign, `npm run fuzz`, holds it to 2 s) and 512 MiB more resident
 * memory. A failure lists its cases: replay one with `FUZZ_SEED=27` and its index, or
 * save them all with `npm run fuzz -- --failures DIR` and `--replay DIR`.
 */
import { expect, it } from 'vitest';
import { BIN } from '../helpers/cli.ts';
import { FORMAT_NAMES } from './spec/cases.ts';
import { listing, runCampaign, table } from './spec/campaign.ts';

it('every generated and mutated file of every format ends as an image, one line or a note', async () => {
  const rep = await runCampaign({
    bin: BIN,
    seed: 27,
    cases: 8 * FORMAT_NAMES.length,
    // One case at a time: beside another test file on two cores, two CLI processes more
    // starved the timing-sensitive browser tests (a 317 ms main-thread task in one run).
    jobs: 1,
    baselineRuns: 1,
    slowSeconds: 10,
    heavyMiB: 512,
    timeoutMs: 30_000,
    rssCapMiB: 2048,
  });
  expect(new Set(rep.results.map((r) => r.format)).size).toBe(FORMAT_NAMES.length);
  // The listing itself is compared, so that a failure prints one line per failing case.
  expect(listing(rep.failures), table(rep)).toBe('');
}, 300_000);
