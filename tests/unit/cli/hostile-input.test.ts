/**
 * The generic defences against hostile input, one module at a time: the strict JSON
 * parser, strict UTF-8, message quoting, the scene loader's byte path and radiance bound,
 * robust quad geometry, the bounded "did you mean" search, option values.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { parseRenderArgs } from '../../../src/cli/args.ts';
import { UsageError } from '../../../src/cli/errors.ts';
import { CliError } from '../../../src/cli/errors.ts';
import { parseDecimalValue, parseIntegerValue, POSITIVE_DECIMAL } from '../../../src/cli/values.ts';
import {
  Film,
  PathTracer,
  RenderStats,
  SceneError,
  compileScene,
  parseScene,
  validateScene,
} from '../../../src/core/index.ts';
import { QUAD_STRIDE, writeQuadRecord } from '../../../src/core/geometry/shapes.ts';
import { Utf8Error, decodeUtf8, findInvalidUtf8 } from '../../../src/core/io/utf8.ts';
import { JsonError, MAX_JSON_DEPTH, lineColumn, parseJson } from '../../../src/core/io/json.ts';
import { printableLine, quote, sanitize } from '../../../src/core/util/message.ts';
import { MAX_RADIANCE, checkTexelRadiance } from '../../../src/core/scene/validate/radiance.ts';
import { LIMITS } from '../../../src/core/scene/format/types.ts';
import { ROOT } from '../../helpers/render.ts';

const base = () =>
  JSON.parse(readFileSync(`${ROOT}tests/fuzz/corpus/valid-base.json`, 'utf8')) as any;
const bytes = (s: string) => new TextEncoder().encode(s);

function sceneError(run: () => unknown): SceneError {
  try {
    run();
  } catch (e) {
    expect(e).toBeInstanceOf(SceneError);
    return e as SceneError;
  }
  throw new Error('expected a SceneError');
}

function jsonError(text: string): JsonError {
  try {
    parseJson(text);
  } catch (e) {
    expect(e).toBeInstanceOf(JsonError);
    return e as JsonError;
  }
  throw new Error(`expected a JsonError for ${JSON.stringify(text)}`);
}

describe('parseJson', () => {
  it('parses what JSON.parse parses, __proto__ as an own key', () => {
    const text = '{"a":[1,-0.5e2,true,false,null,"\\u00e9\\n\\"\\\\\\/"],"__proto__":{"x":1}}';
    const value = parseJson(text) as any;
    expect(value).toEqual(JSON.parse(text));
    expect(Object.getPrototypeOf(value)).toBe(Object.prototype);
    expect(Object.keys(value)).toEqual(['a', '__proto__']);
    expect(({} as any).x).toBeUndefined();
  });

  it('names the line and column of a syntax error (CRLF, tabs and astral characters)', () => {
    expect(jsonError('{\n  "a": 1,\n  "b" 2\n}').message).toBe(
      `line 3, column 7: expected ':' after the key "b", got "2"`,
    );
    expect(jsonError('{\r\n"a":\r\n  x}').message).toMatch(/^line 3, column 3: expected a value/);
    const e = jsonError('["\u{1f600}", x]');
    expect([e.line, e.column]).toEqual([1, 7]);
    expect(lineColumn('a\rb\r\nc', 6)).toEqual({ line: 3, column: 2 });
  });

  it.each([
    ['', 'expected a value, got the end of the file'],
    ['{"a":1,}', `expected a key in double quotes, got "}"`],
    ['[1 2]', `expected ',' or ']' after an array element, got "2"`],
    ['01', 'a number must not have leading zeros'],
    ['1.', 'expected a digit after the decimal point, got the end of the file'],
    ['1e+', 'expected a digit in the exponent'],
    ['-', 'expected a digit in a number'],
    ['"\\x41"', 'invalid escape "\\\\x41\\"" in a string'],
    ['"\\u12"', 'invalid escape'],
    ['"a\nb"', 'control character "\\n" must be escaped inside a string'],
    ['"abc', 'a string is not closed before the end of the file'],
    ['{} []', 'expected the end of the file after the JSON value, got "["'],
    ['\ufeff{}', 'expected a value, got "\\ufeff"'],
    ['NaN', 'expected a value, got "N"'],
    ['\u001b[2J', 'expected a value, got "\\u001b"'],
  ])('rejects %j: %s', (text, message) => {
    const e = jsonError(text);
    expect(e.kind).toBe('syntax');
    expect(e.message).toContain(message);
  });

  it('rejects a key given twice, naming its path and position', () => {
    const e = jsonError('{"shapes": [{}, {"radius": -1,\n "radius": 1}]}');
    expect(e.kind).toBe('duplicate');
    expect(e.path).toBe('shapes[1].radius');
    expect(e.message).toBe('shapes[1].radius appears twice in one object (line 2, column 2)');
    expect(jsonError('{"__proto__": 1, "__proto__": 2}').path).toBe('__proto__');
    expect(jsonError('{"a b": {"\\u001b": 1, "\\u001b": 2}}').message).toMatch(
      /^\["a b"\]\["\\u001b"\] appears twice/,
    );
  });

  it('finds a duplicate key anywhere, whatever the strings hold', () => {
    // Valid text goes through JSON.parse after a scan that counts keys: colons, braces and
    // escaped quotes inside strings must not confuse the count.
    const items = Array.from({ length: 2000 }, (_, i) => ({ name: `a":{[\\${i}`, v: [i, -0.5] }));
    const text = JSON.stringify({ items, tail: { 'k:"}': 1 } });
    expect(parseJson(text)).toEqual(JSON.parse(text));
    const dup = text.replace('"v":[1234,', '"v":0,"v":[1234,');
    const e = jsonError(dup);
    expect(e.kind).toBe('duplicate');
    expect(e.path).toBe('items[1234].v');
    expect(jsonError('[{"a":{"b":1,"b":1}}]').path).toBe('[0].a.b');
  });

  it('bounds nesting without recursion', () => {
    expect(() => parseJson('['.repeat(MAX_JSON_DEPTH) + ']'.repeat(MAX_JSON_DEPTH))).not.toThrow();
    const deep = '['.repeat(MAX_JSON_DEPTH + 1) + ']'.repeat(MAX_JSON_DEPTH + 1);
    expect(jsonError(deep).message).toMatch(/nested deeper than 512 levels/);
    const e = jsonError('['.repeat(1_000_000));
    expect(e.message).toBe(
      `line 1, column ${MAX_JSON_DEPTH + 1}: arrays and objects are nested deeper than 512 levels`,
    );
  });
});

describe('strict UTF-8', () => {
  it.each([
    [[0x61, 0xff], 1, 'byte 0xff is a byte never used in UTF-8'],
    [[0x80], 0, 'a continuation byte without a lead byte'],
    [[0xc0, 0xaf], 0, 'byte 0xc0 is a byte never used'], // overlong '/'
    [[0xe0, 0x80, 0xaf], 0, 'the sequence starting with 0xe0 is broken by 0x80'], // overlong
    [[0xed, 0xa0, 0x80], 0, 'broken by 0xa0'], // a surrogate
    [[0xf4, 0x90, 0x80, 0x80], 0, 'broken by 0x90'], // above U+10FFFF
    [[0x0a, 0x0a, 0x61, 0xe2, 0x82], 3, 'the sequence starting with 0xe2 is cut off'],
  ])('rejects %j at byte %i', (input, offset, detail) => {
    const b = Uint8Array.from(input);
    expect(findInvalidUtf8(b)?.offset).toBe(offset);
    let error: Utf8Error | undefined;
    try {
      decodeUtf8(b);
    } catch (e) {
      error = e as Utf8Error;
    }
    expect(error).toBeInstanceOf(Utf8Error);
    expect(error!.offset).toBe(offset);
    expect(error!.message).toContain(`not valid UTF-8 at byte ${offset} (line `);
    expect(error!.message).toContain(detail);
  });

  it('decodes valid text and drops one leading byte-order mark', () => {
    expect(decodeUtf8(bytes('\ufeffé€\u{1f600}'))).toBe('é€\u{1f600}');
    expect(findInvalidUtf8(bytes('é€\u{1f600}\u{10ffff}'))).toBeUndefined();
  });
});

describe('quote and sanitize', () => {
  it('escapes controls, DEL, C1, format characters, separators, surrogates', () => {
    expect(quote('\u001b[2J\u0000\u007f\u009b\u202e\u200b\u2028\ud800\ue000"\\é'.normalize())).toBe(
      '"\\u001b[2J\\u0000\\u007f\\u009b\\u202e\\u200b\\u2028\\ud800\\ue000\\"\\\\é"',
    );
    expect(sanitize('a\nb\tc')).toBe('a\\nb\\tc');
    expect(printableLine('one\ntwo')).toBe('one\\ntwo');
  });

  it('shows at most ~80 characters, with the length, without splitting a character', () => {
    expect(quote('k'.repeat(100_000))).toBe(`"${'k'.repeat(80)}..." (100000 characters)`);
    expect(quote('\u{1f600}'.repeat(100)).length).toBeLessThan(110);
    expect(quote('\u{1f600}'.repeat(100))).not.toMatch(/[\ud800-\udbff]"/);
    expect(quote('\u0000'.repeat(100))).toBe(`"${'\\u0000'.repeat(13)}..." (100 characters)`);
    expect(quote('abc...')).toBe('"abc..."');
  });
});

describe('parseScene on bytes', () => {
  it('takes the bytes of a file: size checked in bytes, strict UTF-8, BOM dropped', () => {
    const json = JSON.stringify(base());
    expect(parseScene(bytes('\ufeff' + json)).name).toBe('fuzz base');
    const big = new Uint8Array(LIMITS.fileBytes + 1).fill(0x20);
    expect(sceneError(() => parseScene(big)).message).toBe(
      'scene file must be at most 16777216 bytes (16 MiB), got 16777217 bytes',
    );
    // 6 MB of invalid bytes are not 18 MB of U+FFFD: the UTF-8 error is the problem.
    const invalid = new Uint8Array(6_000_000).fill(0xff);
    expect(sceneError(() => parseScene(invalid)).message).toBe(
      'scene file is not valid UTF-8 at byte 0 (line 1): byte 0xff is a byte never used in UTF-8',
    );
  });

  it('rejects two names that only differ in invalid bytes', () => {
    const text = JSON.stringify(base()).replace('"white":', '"\u0001":"x","\u0002":');
    const raw = bytes(text);
    raw[raw.indexOf(1)] = 0xff;
    raw[raw.indexOf(2)] = 0xfe;
    expect(sceneError(() => parseScene(raw)).message).toMatch(
      /^scene file is not valid UTF-8 at byte \d+/,
    );
  });

  it('reports a duplicate key by path', () => {
    const text = JSON.stringify(base()).replace('"radius":0.5', '"radius":-1,"radius":1');
    expect(sceneError(() => parseScene(text)).message).toMatch(
      /^shapes\[1\]\.radius appears twice in one object \(line 1, column \d+\): a key may appear only once$/,
    );
  });
});

describe('radiance bound', () => {
  it('accepts emission and environment up to 1e12 and rejects more', () => {
    const s = base();
    s.materials.light.emission = [MAX_RADIANCE, 0, 0];
    s.environment = [MAX_RADIANCE, MAX_RADIANCE, 0];
    expect(() => validateScene(s)).not.toThrow();
    s.materials.light.emission = [1e38, 0, 0];
    s.environment = [0, 0, -1];
    expect(sceneError(() => validateScene(s)).problems).toEqual([
      'materials.light.emission[0] must be at most 1e12 (the radiance bound, so that sums of ' +
        'samples cannot overflow), got 1e+38',
      'environment[2] must be >= 0, got -1',
    ]);
  });

  it('checks environment-map texels times their scale (the helper for map loaders)', () => {
    const problems: string[] = [];
    const texels = Float32Array.from([1, 2, 3, 4, 5, 6, 7e11, 8, 9, 1, 1, 1]);
    expect(checkTexelRadiance(texels, 2, [1, 1, 1], 'environment.file', problems)).toBe(true);
    expect(checkTexelRadiance(texels, 2, [2, 1, 1], 'environment.file', problems)).toBe(false);
    expect(problems).toEqual([
      'environment.file: texel (0, 1) r times scale (699999977472 * 2 = 1399999954944) must be ' +
        'at most 1e12 (the radiance bound, so that sums of samples cannot overflow)',
    ]);
    problems.length = 0;
    const bad = Float32Array.from([NaN, 0, 0, 0, -1, 0, Infinity, 0, 0]);
    expect(checkTexelRadiance(bad, 3, [1, 1, 1], 'environment.file', problems)).toBe(false);
    expect(problems).toEqual([
      'environment.file: texel (0, 0) r must be a finite number >= 0, got NaN (3 texels break this rule)',
    ]);
  });
});

describe('quads in double precision', () => {
  it('computes the record robustly: no underflow in the cross product', () => {
    const out = new Float64Array(QUAD_STRIDE);
    const area = writeQuadRecord([0, 0, 0], [1e-200, 0, 0], [0, 1, 0], out, 0);
    expect(area).toBe(1e-200);
    expect(out.every(Number.isFinite)).toBe(true);
    expect([out[9], out[10], out[11]]).toEqual([0, 0, 1]);
  });

  it('renders an emitting quad of area ~1e-320 without a single NaN sample', () => {
    const s = base();
    s.shapes[2].u = [1e-160, 0, 0];
    s.shapes[2].v = [0, 0, 1e-160];
    const scene = validateScene(s);
    const tracer = new PathTracer(compileScene(scene), {
      width: 12,
      height: 10,
      maxBounces: 3,
      camera: scene.camera,
    });
    const film = new Film(12, 10);
    const stats = new RenderStats();
    tracer.renderRows(film, 0, 10, 0, 4, stats);
    // Before the light sampler's guard, Inf/Inf made ~80% of these samples NaN.
    expect(stats.rejected).toBe(0);
    expect(film.sums.every(Number.isFinite)).toBe(true);
  });
});

describe('"did you mean" is bounded', () => {
  it('rejects 10,000 shapes naming 10,000 missing materials among 10,000 quickly', () => {
    const s = base();
    s.materials = {};
    s.shapes = [];
    for (let i = 0; i < 10_000; i++) {
      s.materials[`material${i}`] = { type: 'diffuse', albedo: [0.5, 0.5, 0.5] };
      s.shapes.push({ type: 'sphere', center: [0, 0, 0], radius: 1, material: `missing${i}` });
    }
    s.shapes[0].material = 'materal0';
    const t0 = performance.now();
    const error = sceneError(() => validateScene(s));
    // (Measured here only as a bound against the quadratic search: 74 s before.)
    expect(performance.now() - t0).toBeLessThan(5000);
    expect(error.problems).toHaveLength(10_000);
    expect(error.problems[0]).toBe(
      'shapes[0].material names unknown material "materal0" (did you mean "material0"?)',
    );
  });
});

describe('option values', () => {
  it('accepts decimal numbers only', () => {
    for (const ok of ['1', '0.5', '.5', '2.', '1e3', '1E-3', '-0']) {
      expect(() => parseDecimalValue('--x', ok, { ok: () => true, rule: '' })).not.toThrow();
    }
    for (const bad of ['0x10', '', ' 1', '1 ', '+1', 'Infinity', 'NaN', '1_0', '0b1', '1e400']) {
      expect(() => parseDecimalValue('--x', bad, POSITIVE_DECIMAL), bad).toThrow(CliError);
    }
    expect(() => parseIntegerValue('--spp', '1e3', 1, 10)).toThrow(
      '--spp must be an integer in [1, 10], got "1e3"',
    );
  });

  it('--json is a switch: --json=false is an error, not "true"', () => {
    const argv = ['scene.json', '--out', 'x.pfm'];
    expect(parseRenderArgs([...argv, '--json']).json).toBe(true);
    expect(parseRenderArgs(argv).json).toBe(false);
    for (const flag of ['--json=false', '--json=true', '--json=']) {
      expect(() => parseRenderArgs([...argv, flag])).toThrow(UsageError);
    }
    expect(() => parseRenderArgs([...argv, '--exposure', '0x10'])).toThrow(
      '--exposure must be a decimal number > 0, got "0x10"',
    );
    expect(parseRenderArgs([...argv, '--exposure', '1.5e-1']).exposure).toBe(0.15);
  });
});
