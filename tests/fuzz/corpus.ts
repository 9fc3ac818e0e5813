/**
 * The fixed corpus of hostile inputs for `pathwise render`: one case per finding of
 * issue 9 and per rule of the scene format's "Bad input" section. Small scene files are
 * committed byte for byte under tests/fuzz/corpus/ (invalid UTF-8, escape codes and all);
 * large ones (20 MB, 6 MB of invalid UTF-8, 10,000 shapes naming 10,000 missing
 * materials) and the cases that need a device, a pipe or a directory are generated here,
 * deterministically, into a temporary directory.
 *
 * Each case states what the command line must do: exit 0 with a finite image, or exit 2
 * with one printable line matching `message`, within `seconds` and without memory growing
 * past `rssMiB`.
 */
import { mkdirSync, readFileSync, symlinkSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { ROOT } from '../helpers/render.ts';

export const CORPUS_DIR = join(ROOT, 'tests/fuzz/corpus');

export interface CorpusCase {
  name: string;
  /** The finding of issue 9 (F…) or the format rule (R…) the case covers. */
  covers: string;
  /** Builds the inputs in `dir` and returns the arguments after `pathwise`. */
  args: (dir: string) => string[];
  /** Piped into the CLI's stdin (a shell command's output). */
  pipeFrom?: string;
  status: 0 | 2;
  message?: RegExp;
  /** Must not match (e.g. the size of the decoded text instead of the file's). */
  notMessage?: RegExp;
  /** Wall-clock limit (a hang fails the case). */
  seconds?: number;
  rssMiB?: number;
}

/** The small valid scene of the corpus (12 x 10 pixels, 2 spp): valid cases render fast. */
export function baseScene(): any {
  return JSON.parse(readFileSync(join(CORPUS_DIR, 'valid-base.json'), 'utf8'));
}

const file = (name: string) => () => [
  'render',
  join(CORPUS_DIR, name),
  '--out',
  join(outDir, `${name}.pfm`),
];

/** Where cases write their images; set by the test's beforeAll. */
let outDir = '';
export function setOutDir(dir: string): void {
  outDir = dir;
}
export function outPath(name: string): string {
  return join(outDir, `${name}.pfm`);
}

function write(dir: string, name: string, data: string | Uint8Array): string {
  const path = join(dir, name);
  writeFileSync(path, data);
  return path;
}

/** 10,000 materials and 10,000 shapes that each name a different missing material. */
function missingMaterials(count: number, nameLength: number): string {
  const s = baseScene();
  const pad = (prefix: string, i: number) => (prefix + String(i)).padEnd(nameLength, 'x');
  s.materials = {};
  for (let i = 0; i < count; i++) {
    s.materials[pad('m', i)] = { type: 'diffuse', albedo: [0.5, 0.5, 0.5] };
  }
  s.shapes = [];
  for (let i = 0; i < count; i++) {
    s.shapes.push({ type: 'sphere', center: [i, 0, 0], radius: 0.5, material: pad('q', i) });
  }
  return JSON.stringify(s);
}

export const CORPUS: CorpusCase[] = [
  // ---- Findings of issue 9 -------------------------------------------------------------
  {
    name: 'out in a missing directory',
    covers: 'F1 crash: --out in a missing directory',
    args: (dir) => [
      'render',
      join(CORPUS_DIR, 'valid-base.json'),
      '--out',
      join(dir, 'missing', 'x.pfm'),
    ],
    status: 2,
    message: /cannot write .*x\.pfm: the directory .*missing does not exist/,
  },
  {
    name: 'out is a directory',
    covers: 'F1 crash: --out is a directory',
    args: (dir) => {
      mkdirSync(join(dir, 'dir.pfm'), { recursive: true });
      return ['render', join(CORPUS_DIR, 'valid-base.json'), '--out', join(dir, 'dir.pfm')];
    },
    status: 2,
    message: /cannot write .*dir\.pfm: it is a directory/,
  },
  {
    name: 'out is /dev/full (through a link named full.pfm)',
    covers: 'F1 crash: --out is a full device',
    args: (dir) => {
      symlinkSync('/dev/full', join(dir, 'full.pfm'));
      return ['render', join(CORPUS_DIR, 'valid-base.json'), '--out', join(dir, 'full.pfm')];
    },
    status: 2,
    message: /cannot write .*full\.pfm: it is a character device, not a regular file/,
  },
  {
    name: 'out is checked before a long render',
    covers: 'F2 the output was opened only after the render',
    args: (dir) => {
      const s = baseScene();
      s.settings = { width: 1024, height: 1024, maxBounces: 8, spp: 1048576 / 16 };
      const scene = write(dir, 'long.json', JSON.stringify(s));
      return ['render', scene, '--out', join(dir, 'missing', 'long.pfm')];
    },
    status: 2,
    message: /the directory .* does not exist/,
    seconds: 10,
  },
  {
    name: 'scene is /dev/zero',
    covers: 'F3 hang/memory: /dev/zero',
    args: () => ['render', '/dev/zero', '--out', outPath('zero')],
    status: 2,
    message:
      /\/dev\/zero: scene file must be at most 16777216 bytes \(16 MiB\), got at least 16777217 bytes/,
    rssMiB: 400,
  },
  {
    name: 'scene is /dev/urandom',
    covers: 'F3 hang/memory: /dev/urandom',
    args: () => ['render', '/dev/urandom', '--out', outPath('urandom')],
    status: 2,
    message: /got at least 16777217 bytes/,
    rssMiB: 400,
  },
  {
    name: "scene is a pipe: yes '[' | pathwise render /dev/stdin",
    covers: 'F3 hang/memory: a pipe',
    args: () => ['render', '/dev/stdin', '--out', outPath('stdin')],
    pipeFrom: "yes '['",
    status: 2,
    message: /\/dev\/stdin: scene file must be at most 16777216 bytes \(16 MiB\), got at least/,
    rssMiB: 400,
  },
  {
    name: 'a valid scene through a pipe',
    covers: 'F3 a pipe is read to its end (cat valid-base.json | … /dev/stdin)',
    args: () => ['render', '/dev/stdin', '--out', outPath('stdin-valid')],
    pipeFrom: `cat '${join(CORPUS_DIR, 'valid-base.json')}'`,
    status: 0,
  },
  {
    name: '10,000 shapes naming 10,000 missing materials',
    covers: 'F4 quadratic "did you mean"',
    args: (dir) => [
      'render',
      write(dir, 'missing-10k.json', missingMaterials(10_000, 6)),
      '--out',
      outPath('missing-10k'),
    ],
    status: 2,
    message: /shapes\[0\]\.material names unknown material "q0xxxx" .*\(and 9999 more problems\)/,
    seconds: 10,
  },
  {
    name: '1,000 x 1,000 missing materials with 64-character names',
    covers: 'F4 quadratic "did you mean" (long names)',
    args: (dir) => [
      'render',
      write(dir, 'missing-1k.json', missingMaterials(1_000, 64)),
      '--out',
      outPath('missing-1k'),
    ],
    status: 2,
    message: /names unknown material "q0x+"/,
    seconds: 10,
  },
  {
    name: 'emission 1e38',
    covers: 'F5 film overflow: emission >= 1e38',
    args: file('radiance-emission-1e38.json'),
    status: 2,
    message: /materials\.light\.emission\[0\] must be at most 1e12 \(the radiance bound/,
  },
  {
    name: 'emission 2e37 summed over 64 samples',
    covers: 'F5 film overflow: 1e38 summed over a few samples',
    args: file('radiance-summed-2e37.json'),
    status: 2,
    message: /emission\[0\] must be at most 1e12/,
  },
  {
    name: 'environment 1e38',
    covers: 'F5 film overflow: environment >= 1e38',
    args: file('radiance-environment-1e38.json'),
    status: 2,
    message: /environment\[0\] must be at most 1e12/,
  },
  {
    name: 'JSON syntax error',
    covers: 'F6 raw V8 snippet over two lines, no line or column',
    args: file('syntax-trailing-comma.json'),
    status: 2,
    message: /not valid JSON: line 27, column 3: expected a key in double quotes, got "\}"/,
  },
  {
    name: 'terminal escape codes and NUL in a value',
    covers: 'F7 escape codes and NUL echoed raw',
    args: file('escape-codes.json'),
    status: 2,
    message: /unknown material "\\u001b\[2J\\u001b\[H\\u0000evil\\u009b31m"/,
  },
  {
    name: 'a 100,000-character unknown key',
    covers: 'F8 a long key quoted whole',
    args: (dir) => {
      const s = baseScene();
      s['k'.repeat(100_000)] = 1;
      return ['render', write(dir, 'long-key.json', JSON.stringify(s)), '--out', outPath('k')];
    },
    status: 2,
    message: /^pathwise: .{0,120}\["k{60,80}\.\.\." \(100000 characters\)\] is not a known key$/,
  },
  {
    name: 'no arguments at all',
    covers: 'F9 no arguments: exit 2 with nothing on stderr',
    args: () => [],
    status: 2,
    message: /no command given; usage: pathwise render SCENE\.json --out/,
  },
  {
    name: '6 MB of invalid UTF-8',
    covers: 'F10 the size reported was that of the decoded text',
    args: (dir) => [
      'render',
      write(dir, 'invalid-6mb.json', new Uint8Array(6_000_000).fill(0xff)),
      '--out',
      outPath('invalid-6mb'),
    ],
    status: 2,
    message: /scene file is not valid UTF-8 at byte 0 \(line 1\): byte 0xff/,
    notMessage: /16 MiB|18000000/,
  },
  {
    name: 'duplicate key: radius -1 then radius 1',
    covers: 'F11 duplicate keys, last one wins',
    args: file('duplicate-radius.json'),
    status: 2,
    message: /shapes\[1\]\.radius appears twice in one object \(line 78, column 21\)/,
  },
  {
    name: 'duplicate key: two formats',
    covers: 'F11 duplicate keys (two formats)',
    args: file('duplicate-format.json'),
    status: 2,
    message: /format appears twice in one object \(line 3, column 3\)/,
  },
  {
    name: 'invalid UTF-8 material names \\xFF and \\xFE',
    covers: 'F12 invalid UTF-8 became U+FFFD, two names one key',
    args: file('invalid-utf8-names.json'),
    status: 2,
    message: /not valid UTF-8 at byte 351 \(line 29\): byte 0xff/,
  },
  {
    name: 'emitting quad whose area underflows (u = [1e-200,0,0], v = [0,0,1e-200])',
    covers: 'F13 quad area underflow: NaN samples dropped silently',
    args: file('quad-area-underflow-light.json'),
    status: 2,
    message:
      /shapes\[2\] is a degenerate quad: its area \|u x v\| underflows to 0 in double precision/,
  },
  {
    name: '--json=false',
    covers: 'F14 --json=false turned JSON on',
    args: () => [
      'render',
      join(CORPUS_DIR, 'valid-base.json'),
      '--out',
      outPath('json-false'),
      '--json=false',
    ],
    status: 2,
    message:
      /--json is a switch and takes no value: give --json or leave it out, got "--json=false"/,
  },
  {
    name: '--exposure 0x10',
    covers: 'F14 --exposure 0x10 read as 16',
    args: () => [
      'render',
      join(CORPUS_DIR, 'valid-base.json'),
      '--out',
      join(outDir, 'exposure.png'),
      '--exposure',
      '0x10',
    ],
    status: 2,
    message: /--exposure must be a decimal number > 0, got "0x10"/,
  },

  // ---- Rules of "Bad input" (docs/scene-format.md) -------------------------------------
  { name: 'valid scene', covers: 'R0 the base renders', args: file('valid-base.json'), status: 0 },
  {
    name: 'leading byte-order mark',
    covers: 'R1 a leading BOM is ignored',
    args: file('valid-bom.json'),
    status: 0,
  },
  {
    name: 'unknown key',
    covers: 'R2 unknown keys are an error',
    args: file('unknown-key.json'),
    status: 2,
    message: /shapes\[1\]\.radus is not a known key \(did you mean radius\?\)/,
  },
  {
    name: 'missing required key',
    covers: 'R2 a file that breaks a rule names the path',
    args: file('missing-camera.json'),
    status: 2,
    message: /camera is required but missing/,
  },
  {
    name: 'not an object',
    covers: 'R2 the scene is an object',
    args: file('not-an-object.json'),
    status: 2,
    message: /scene must be an object, got \[1, 2, 3\]/,
  },
  {
    name: '__proto__ key',
    covers: 'R2 __proto__ is an ordinary (unknown) key',
    args: file('proto-key.json'),
    status: 2,
    message: /__proto__ is not a known key/,
  },
  {
    name: 'truncated JSON',
    covers: 'R3 syntax errors name line and column',
    args: file('syntax-truncated.json'),
    status: 2,
    message: /not valid JSON: line \d+, column \d+: .*got the end of the file/,
  },
  {
    name: 'empty file',
    covers: 'R3 syntax errors name line and column',
    args: file('syntax-empty.json'),
    status: 2,
    message: /not valid JSON: line 1, column 1: expected a value, got the end of the file/,
  },
  {
    name: 'a comment',
    covers: 'R3 RFC 8259 JSON only',
    args: file('syntax-comment.json'),
    status: 2,
    message: /not valid JSON: line 1, column 1: expected a value, got "\/"/,
  },
  {
    name: 'NaN literal',
    covers: 'R3 RFC 8259 JSON only',
    args: file('syntax-nan.json'),
    status: 2,
    message: /line 20, column 13: expected a value, got "N"/,
  },
  {
    name: 'hexadecimal number',
    covers: 'R3 RFC 8259 JSON only',
    args: file('number-hex.json'),
    status: 2,
    message: /line 20, column 14: expected ',' or '\}' after an object member, got "x"/,
  },
  {
    name: 'number with a leading zero',
    covers: 'R3 RFC 8259 JSON only',
    args: file('number-leading-zero.json'),
    status: 2,
    message: /line 20, column 13: a number must not have leading zeros/,
  },
  {
    name: 'raw tab inside a string',
    covers: 'R3 RFC 8259 JSON only',
    args: file('syntax-control-in-string.json'),
    status: 2,
    message: /line 3, column 16: control character "\\t" must be escaped inside a string/,
  },
  {
    name: 'arrays nested 100,000 deep',
    covers: 'R3 nesting is bounded (no stack overflow, no million arrays)',
    args: (dir) => ['render', write(dir, 'deep.json', '['.repeat(100_000)), '--out', outPath('d')],
    status: 2,
    message: /line 1, column 513: arrays and objects are nested deeper than 512 levels/,
  },
  {
    name: 'number that overflows a double',
    covers: 'R4 every number is finite',
    args: file('number-overflow.json'),
    status: 2,
    message: /shapes\[1\]\.radius must be a finite number, got Infinity/,
  },
  {
    name: 'radiance exactly at the bound',
    covers: 'R5 radiance <= 1e12 is accepted',
    args: file('radiance-at-bound.json'),
    status: 0,
  },
  {
    name: 'radiance just over the bound',
    covers: 'R5 radiance > 1e12 is an error',
    args: file('radiance-over-bound.json'),
    status: 2,
    message: /environment\[0\] must be at most 1e12 .*got 1000001000000/,
  },
  {
    name: 'quad with parallel edges',
    covers: 'R6 quads span a non-zero area',
    args: file('quad-parallel.json'),
    status: 2,
    message: /shapes\[0\] is a degenerate quad: u and v are parallel or zero \(area 0\)/,
  },
  {
    name: 'quad whose area overflows',
    covers: 'R6 quads span a finite area',
    args: file('quad-area-overflow.json'),
    status: 2,
    message: /shapes\[2\] is too large: its area \|u x v\| overflows double precision/,
  },
  {
    name: 'emitting quad of area 1e-320 (valid: renders with no NaN)',
    covers: 'R6 a tiny but non-zero area is valid and renders finite',
    args: (dir) => [
      'render',
      join(CORPUS_DIR, 'quad-tiny-light.json'),
      '--out',
      outPath('tiny'),
      '--json',
    ],
    status: 0,
  },
  {
    name: 'file over 16 MiB',
    covers: 'R7 the file is at most 16 MiB; the message gives the size of the file',
    args: (dir) => {
      const s = JSON.stringify(baseScene());
      const big = write(dir, 'big.json', s + ' '.repeat(20 * 1024 * 1024 - s.length));
      return ['render', big, '--out', outPath('big')];
    },
    status: 2,
    message: /big\.json: scene file must be at most 16777216 bytes \(16 MiB\), got 20971520 bytes/,
    rssMiB: 400,
  },
  {
    name: 'more than 100,000 shapes',
    covers: 'R7 at most 100,000 shapes',
    args: (dir) => {
      const s = baseScene();
      const sphere = { type: 'sphere', center: [0, 0, 0], radius: 1, material: 'white' };
      s.shapes = Array.from({ length: 100_001 }, () => sphere);
      return ['render', write(dir, 'shapes.json', JSON.stringify(s)), '--out', outPath('s')];
    },
    status: 2,
    message: /shapes has 100001 entries, more than the limit of 100000/,
  },
  {
    name: 'width x height over the limit',
    covers: 'R7 width x height at most 16,777,216',
    args: file('limit-pixels.json'),
    status: 2,
    message:
      /settings\.width \* settings\.height must be at most 16777216 pixels, got 4097 \* 4096/,
  },
  {
    name: 'spp over the limit',
    covers: 'R7 spp at most 1,048,576',
    args: file('limit-spp.json'),
    status: 2,
    message: /settings\.spp must be an integer in \[1, 1048576\], got 1048577/,
  },
  {
    name: 'maxBounces over the limit',
    covers: 'R7 maxBounces at most 64',
    args: file('limit-bounces.json'),
    status: 2,
    message: /settings\.maxBounces must be an integer in \[0, 64\], got 65/,
  },
  {
    name: 'bidirectional override in a key',
    covers: 'R8 messages are printable',
    args: file('bidi-key.json'),
    status: 2,
    message: /\["\\u202egnp\.exe"\] is not a known key/,
  },
  {
    name: 'lone surrogate escape in a value',
    covers: 'R8 messages are printable',
    args: file('lone-surrogate.json'),
    status: 2,
    message: /unknown material "\\ud800"/,
  },
  {
    name: 'escape codes in an option name',
    covers: 'R8 messages are printable (arguments too)',
    args: () => ['render', join(CORPUS_DIR, 'valid-base.json'), '--\u001b[2Jx', '1'],
    status: 2,
    message: /unknown option --\\u001b\[2Jx/,
  },
  {
    name: 'scene is a directory',
    covers: 'R9 a scene path that cannot be read',
    args: () => ['render', CORPUS_DIR, '--out', outPath('dir')],
    status: 2,
    message: /cannot read .*corpus: it is a directory/,
  },
];
