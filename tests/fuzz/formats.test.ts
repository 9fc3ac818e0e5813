/**
 * Every file format in tests/fuzz/formats.ts under the hostile-input contract: valid
 * samples decode; every truncation, lying header and NaN variant is a FormatError of one
 * printable line naming the format (never another exception, never a slow or huge
 * allocation); random byte mutations (fast-check, fixed seed) either decode to a sane
 * value or give such a FormatError.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { FormatError } from '../../src/core/index.ts';
import { PRINTABLE_LINE } from '../helpers/cli.ts';
import { FORMATS, type FormatEntry } from './formats.ts';

const SEED = Number(process.env.FUZZ_SEED ?? 20250109);
const SCALE = Number(process.env.FUZZ_RUNS_SCALE ?? 1);

/**
 * Decoding `bytes` throws a FormatError of `format` with one printable line, quickly.
 * (Decoders may be asynchronous, as glTF's is: its resources and images load by promise.)
 */
async function expectFormatError(
  format: FormatEntry,
  bytes: Uint8Array,
  message?: RegExp,
): Promise<void> {
  // CPU time of this process (vitest runs each test file in a process of its
  // own), not wall-clock time: what the bound is about is the work done (an
  // allocation sized by the header, a read of it), which a loaded machine
  // pausing the process between two instructions does not add to.
  const t0 = process.cpuUsage();
  let error: unknown;
  try {
    await format.decode(bytes);
  } catch (e) {
    error = e;
  }
  const used = process.cpuUsage(t0);
  const ms = (used.user + used.system) / 1000;
  expect(error, 'expected a FormatError, but the file was accepted').toBeInstanceOf(FormatError);
  const e = error as FormatError;
  expect(e.format).toBe(format.name);
  expect(e.message.startsWith(`${format.name}: `), e.message).toBe(true);
  expect(PRINTABLE_LINE.test(e.message), JSON.stringify(e.message)).toBe(true);
  expect(e.message.length).toBeLessThan(500);
  if (message) expect(e.message).toMatch(message);
  // A lying header must be caught before anything sized by it is allocated or read.
  expect(ms).toBeLessThan(250);
}

describe.each(FORMATS.map((f) => [f.name, f] as const))('%s', (_, format) => {
  it('decodes its valid samples', async () => {
    for (const bytes of format.samples()) format.check(await format.decode(bytes));
  });

  it('rejects every truncation of every sample with a FormatError', async () => {
    for (const bytes of format.samples()) {
      for (let n = 0; n < bytes.length; n++) {
        const prefix = bytes.subarray(0, n);
        // A text format without a terminator (OBJ) has prefixes that are whole files:
        // those must decode to a sane value; every other prefix is a FormatError.
        if (format.validPrefix?.(prefix)) format.check(await format.decode(prefix));
        else await expectFormatError(format, prefix);
      }
    }
  });

  it.each(format.lyingHeaders().map((c) => [c.name, c] as const))(
    'rejects a lying header: %s',
    (__, c) => expectFormatError(format, c.bytes, c.message),
  );

  it.each(format.nonFinite().map((c) => [c.name, c] as const))(
    'rejects non-finite data: %s',
    (__, c) => expectFormatError(format, c.bytes, c.message),
  );

  it.each((format.others?.() ?? []).map((c) => [c.name, c] as const))('rejects: %s', (__, c) =>
    expectFormatError(format, c.bytes, c.message),
  );

  it('random byte mutations: a sane value or a FormatError, nothing else', async () => {
    const samples = format.samples();
    const mutation = fc.record({
      sample: fc.nat({ max: samples.length - 1 }),
      edits: fc.array(
        fc.record({ at: fc.nat(), byte: fc.integer({ min: 0, max: 255 }), insert: fc.boolean() }),
        { minLength: 1, maxLength: 4 },
      ),
    });
    await fc.assert(
      fc.asyncProperty(mutation, async ({ sample, edits }) => {
        const b = Array.from(samples[sample]);
        for (const e of edits) {
          if (e.insert) b.splice(e.at % (b.length + 1), 0, e.byte);
          else if (b.length > 0) b[e.at % b.length] = e.byte;
        }
        const bytes = Uint8Array.from(b);
        let value: unknown;
        try {
          value = await format.decode(bytes);
        } catch (e) {
          expect(e).toBeInstanceOf(FormatError);
          expect(PRINTABLE_LINE.test((e as Error).message)).toBe(true);
          return;
        }
        format.check(value);
      }),
      { seed: SEED, numRuns: Math.round(2000 * SCALE) },
    );
  });
});
