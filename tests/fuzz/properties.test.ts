/**
 * Property-based fuzzing (fast-check, fixed seed and run counts): mutated valid scenes and
 * argument lists must meet the contract. Most properties run in-process against the
 * loader, the JSON parser, the UTF-8 decoder and the argument parser (thousands of runs in
 * seconds); a sample runs through the real command line, under a time limit and a memory
 * cap, since spawning Node costs ~0.1 s a run.
 *
 * Contract (issue 9): a scene is either accepted, and then renders a finite image, or
 * rejected with a SceneError whose message is one printable line (the CLI: exit 0 with a
 * finite image, or exit 2 with one printable line; never exit 1, a hang or runaway memory).
 *
 * Run counts and the seed are fixed so CI is reproducible; FUZZ_RUNS_SCALE=10 runs ten
 * times as many cases locally, FUZZ_SEED picks another seed.
 */
import fc from 'fast-check';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import {
  Film,
  PathTracer,
  RenderStats,
  SceneError,
  compileScene,
  parseScene,
} from '../../src/core/index.ts';
import { parseRenderArgs } from '../../src/cli/args.ts';
import { UsageError } from '../../src/cli/errors.ts';
import { decodeUtf8, Utf8Error } from '../../src/core/io/utf8.ts';
import { JsonError, parseJson, parseJsonStrict } from '../../src/core/io/json.ts';
import { quote, sanitize } from '../../src/core/util/message.ts';
import { MAX_RADIANCE } from '../../src/core/scene/validate/radiance.ts';
import { PRINTABLE_LINE, expectContract, runCli } from '../helpers/cli.ts';
import { CORPUS_DIR } from './corpus.ts';
import { mutatedArgs, mutatedScene } from './mutate.ts';
import { sceneNeedsFiles } from '../../src/core/index.ts';

const SEED = Number(process.env.FUZZ_SEED ?? 20250109);
const SCALE = Number(process.env.FUZZ_RUNS_SCALE ?? 1);
const runs = (n: number) => Math.max(1, Math.round(n * SCALE));

/** What the runs of this file did, for the report (printed at the end). */
const report: string[] = [];
afterAll(() => {
  console.log(`fuzz properties (seed ${SEED}):\n  ${report.join('\n  ')}`);
});

function timed<T>(label: string, numRuns: number, body: () => T): T {
  const t0 = performance.now();
  const result = body();
  report.push(`${label}: ${numRuns} runs, ${((performance.now() - t0) / 1000).toFixed(2)} s`);
  return result;
}

/** A message is one printable line of bounded length. */
function expectPrintable(message: string): void {
  expect(PRINTABLE_LINE.test(message), JSON.stringify(message)).toBe(true);
  expect(message.length, message).toBeLessThan(1200);
}

/** Renders 1 spp of a tiny image in-process; every pixel sum must be finite. */
function renderTiny(sceneBytes: Uint8Array): { accepted: boolean; rejected: number } {
  let scene;
  try {
    scene = parseScene(sceneBytes);
  } catch (e) {
    expect(e).toBeInstanceOf(SceneError);
    const error = e as SceneError;
    expectPrintable(error.message);
    for (const p of error.problems.slice(0, 50)) expectPrintable(p);
    return { accepted: false, rejected: 0 };
  }
  // Accepted: the bound the loader promises holds, and the image is finite.
  for (const m of Object.values(scene.materials)) {
    for (const c of m.emission) expect(c >= 0 && c <= MAX_RADIANCE).toBe(true);
  }
  // A scene that names mesh or map files needs them read (asynchronously) before it can
  // be compiled: the command-line property below renders those, files and all.
  if (sceneNeedsFiles(scene)) return { accepted: true, rejected: 0 };
  const width = 6;
  const height = 4;
  const tracer = new PathTracer(compileScene(scene), {
    width,
    height,
    maxBounces: Math.min(scene.settings.maxBounces, 4),
    camera: scene.camera,
  });
  const film = new Film(width, height);
  const stats = new RenderStats();
  tracer.renderRows(film, 0, height, 0, 1, stats);
  expect(film.sums.every(Number.isFinite)).toBe(true);
  expect(film.hi.every(Number.isInteger) && film.lo.every(Number.isInteger)).toBe(true);
  expect(film.mean().every(Number.isFinite)).toBe(true);
  return { accepted: true, rejected: stats.rejected };
}

describe('properties, in-process', () => {
  it('mutated scenes: accepted and rendered finite, or rejected with one printable line', () => {
    const numRuns = runs(1500);
    let accepted = 0;
    let rejectedSamples = 0;
    timed('loader on mutated scenes', numRuns, () =>
      fc.assert(
        fc.property(mutatedScene, ({ bytes }) => {
          const r = renderTiny(bytes);
          if (r.accepted) accepted++;
          rejectedSamples += r.rejected;
        }),
        { seed: SEED, numRuns },
      ),
    );
    report.push(
      `  of which accepted ${accepted}; non-finite samples rejected by the film: ${rejectedSamples}`,
    );
    // The generator must exercise both sides of the contract.
    expect(accepted).toBeGreaterThan(numRuns / 20);
    expect(accepted).toBeLessThan(numRuns * 0.9);
  });

  it('argument lists: valid values only, or a UsageError of one printable line', () => {
    const numRuns = runs(3000);
    let accepted = 0;
    timed('argument parser on mutated argument lists', numRuns, () =>
      fc.assert(
        fc.property(mutatedArgs('scene.json', 'x.pfm'), (argv) => {
          let args;
          try {
            args = parseRenderArgs(argv);
          } catch (e) {
            expect(e).toBeInstanceOf(UsageError);
            expectPrintable((e as Error).message);
            return;
          }
          expect(args.out).toMatch(/\.(pfm|png)$/i);
          expect(Number.isFinite(args.exposure) && args.exposure > 0).toBe(true);
          expect(typeof args.json).toBe('boolean');
          for (const v of [args.spp, args.width, args.height, args.bounces, args.threads]) {
            if (v !== undefined) expect(Number.isSafeInteger(v)).toBe(true);
          }
          expect(Number.isSafeInteger(args.seed)).toBe(true);
          accepted++;
          // Switches never carry a value, numbers are never hexadecimal or padded.
          expect(argv.some((a) => a.startsWith('--json='))).toBe(false);
          const exposure = argv.indexOf('--exposure');
          if (exposure >= 0) expect(argv[exposure + 1]).toMatch(/^-?[0-9.]+(e[-+]?[0-9]+)?$/i);
        }),
        { seed: SEED, numRuns },
      ),
    );
    report.push(`  of which accepted ${accepted}`);
    expect(accepted).toBeGreaterThan(numRuns / 20);
  });

  it('JSON parser: the same values as JSON.parse on any JSON', () => {
    const numRuns = runs(1500);
    timed('parseJson vs JSON.parse on generated JSON', numRuns, () =>
      fc.assert(
        fc.property(fc.jsonValue(), fc.constantFrom(0, 1, '\t', ' \r\n'), (value, indent) => {
          const text = JSON.stringify(value, null, indent as any);
          expect(parseJson(text)).toEqual(JSON.parse(text));
          // parseJson takes JSON.parse for valid text: the hand-written parser on its own.
          expect(parseJsonStrict(text)).toEqual(JSON.parse(text));
        }),
        { seed: SEED, numRuns },
      ),
    );
  });

  it('JSON parser: fails exactly when JSON.parse fails (or on a duplicate key)', () => {
    const numRuns = runs(3000);
    const jsonish = fc.oneof(
      fc.string({ unit: 'binary', maxLength: 20 }),
      fc
        .tuple(fc.jsonValue({ maxDepth: 3 }), fc.nat(), fc.string({ unit: 'binary', maxLength: 3 }))
        .map(([v, at, insert]) => {
          const t = JSON.stringify(v);
          const i = at % (t.length + 1);
          return t.slice(0, i) + insert + t.slice(i + (at % 2));
        }),
    );
    timed('parseJson vs JSON.parse on mutated JSON text', numRuns, () =>
      fc.assert(
        fc.property(jsonish, (text) => {
          let expected: unknown;
          let native = true;
          try {
            expected = JSON.parse(text);
          } catch {
            native = false;
          }
          // The fast path (JSON.parse) and the hand-written parser alone agree on every text.
          let strict: unknown;
          try {
            strict = parseJsonStrict(text);
          } catch (e) {
            strict = e;
          }
          try {
            const value = parseJson(text);
            expect(native, text).toBe(true);
            expect(value).toEqual(expected);
            expect(strict).toEqual(value);
          } catch (e) {
            expect(e).toBeInstanceOf(JsonError);
            expectPrintable((e as Error).message);
            if ((e as JsonError).kind === 'syntax') expect(native, text).toBe(false);
            expect(strict).toBeInstanceOf(JsonError);
            expect((strict as Error).message).toBe((e as Error).message);
          }
        }),
        { seed: SEED, numRuns },
      ),
    );
  });

  it('UTF-8: rejected exactly when TextDecoder (fatal) rejects, at the first bad byte', () => {
    const numRuns = runs(3000);
    const fatal = new TextDecoder('utf-8', { fatal: true });
    const bytes = fc.oneof(
      fc.uint8Array({ maxLength: 24 }),
      fc
        .tuple(
          fc.string({ unit: 'grapheme', maxLength: 8 }),
          fc.nat(),
          fc.integer({ min: 0, max: 255 }),
        )
        .map(([s, at, b]) => {
          const u = new TextEncoder().encode(s);
          if (u.length > 0) u[at % u.length] = b;
          return u;
        }),
    );
    timed('decodeUtf8 vs TextDecoder', numRuns, () =>
      fc.assert(
        fc.property(bytes, (b) => {
          let expected: string | undefined;
          try {
            expected = fatal.decode(b);
          } catch {
            expected = undefined;
          }
          try {
            expect(decodeUtf8(b)).toBe(expected);
          } catch (e) {
            if (!(e instanceof Utf8Error)) throw e;
            expect(expected).toBeUndefined();
            // Everything before the offset is valid; the offset itself is not.
            expect(() => fatal.decode(b.subarray(0, e.offset))).not.toThrow();
            expect(() => fatal.decode(b.subarray(0, e.offset + 4))).toThrow();
          }
        }),
        { seed: SEED, numRuns },
      ),
    );
  });

  it('quote and sanitize: printable, one line, bounded, whatever the string', () => {
    const numRuns = runs(3000);
    timed('quote/sanitize on arbitrary strings', numRuns, () =>
      fc.assert(
        fc.property(fc.string({ unit: 'binary', maxLength: 400 }), (s) => {
          for (const shown of [quote(s), sanitize(s)]) {
            expect(PRINTABLE_LINE.test(shown), JSON.stringify(shown)).toBe(true);
            expect(shown.length).toBeLessThanOrEqual(120);
          }
        }),
        { seed: SEED, numRuns },
      ),
    );
  });
});

describe('properties, through the real command line (a sample)', () => {
  const dir = mkdtempSync(join(tmpdir(), 'pathwise-fuzz-'));

  it('mutated scenes: exit 0 with a finite image or exit 2 with one line', async () => {
    const numRuns = runs(24);
    const samples = fc.sample(mutatedScene, { seed: SEED, numRuns });
    const t0 = performance.now();
    let ok = 0;
    for (const [i, s] of samples.entries()) {
      const scene = join(dir, `m${i}.json`);
      writeFileSync(scene, s.bytes);
      const out = join(dir, `m${i}.pfm`);
      const args = ['render', scene, '--out', out, '--width', '8', '--height', '6'];
      const r = await runCli([...args, '--spp', '1', '--threads', '1'], {
        timeoutMs: 20_000,
        rssCapMiB: 600,
      });
      expectContract(r, out);
      if (r.status === 0) ok++;
    }
    report.push(
      `CLI on mutated scenes: ${numRuns} runs (${ok} rendered), ${((performance.now() - t0) / 1000).toFixed(1)} s`,
    );
  });

  it('mutated argument lists: exit 0 with a finite image or exit 2 with one line', async () => {
    const numRuns = runs(16);
    const scene = join(CORPUS_DIR, 'valid-base.json');
    const out = join(dir, 'a.pfm');
    // Half of them with only option-value pairs appended, so that some are accepted and
    // the whole path to a written image is exercised too.
    const samples = [
      ...fc.sample(mutatedArgs(scene, out), { seed: SEED, numRuns: numRuns / 2 }),
      ...fc.sample(mutatedArgs(scene, out, { pairsOnly: true }), {
        seed: SEED,
        numRuns: numRuns / 2,
      }),
    ];
    const t0 = performance.now();
    let ok = 0;
    for (const argv of samples) {
      const r = await runCli(['render', ...argv], { timeoutMs: 20_000, rssCapMiB: 600 });
      // The output, if the arguments still name one that was written.
      const at = argv.lastIndexOf('--out');
      expectContract(r, r.status === 0 && at >= 0 ? argv[at + 1] : undefined);
      if (r.status === 0) ok++;
    }
    report.push(
      `CLI on mutated argument lists: ${numRuns} runs (${ok} rendered), ${((performance.now() - t0) / 1000).toFixed(1)} s`,
    );
  });
});
