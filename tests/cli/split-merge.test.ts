/**
 * `pathwise render --samples A:B` and `pathwise merge`, run as a user runs
 * them: parts cut anywhere, rendered with any thread count and merged in
 * any order give the bytes of one run (.film, PFM and PNG); every mismatch
 * is refused with one line; missing ranges are named; damaged files get
 * one clear error.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { encodeFilmFile } from '../../src/core/index.ts';
import {
  expectRefusal,
  pathwise,
  pathwiseOk,
  readFilm,
  tempDir,
  writeCornell,
} from '../helpers/batch-cli.ts';

const dir = tempDir('merge');
const SPP = 12;
let scene: string;
const at = (name: string) => join(dir, name);

function renderPart(a: number, b: number, out: string, extra: string[] = []): void {
  pathwiseOk([
    'render',
    scene,
    '--spp',
    String(SPP),
    '--samples',
    `${a}:${b}`,
    '--out',
    out,
    ...extra,
  ]);
}

function same(a: string, b: string): boolean {
  return readFileSync(a).equals(readFileSync(b));
}

beforeAll(() => {
  scene = writeCornell(dir, { width: 24, height: 16, spp: SPP });
  for (const ext of ['film', 'pfm', 'png']) {
    pathwiseOk(['render', scene, '--threads', '2', '--out', at(`full.${ext}`)]);
  }
  // The parts used by the refusal tests.
  renderPart(0, 6, at('a.film'));
  renderPart(6, 12, at('b.film'));
});

describe('split and merge', () => {
  it('gives the bytes of one run for any cut, thread count and order', () => {
    const splits = [
      [0, 1, 12],
      [0, 5, 6, 7, 12],
    ];
    splits.forEach((cuts, k) => {
      const parts: string[] = [];
      for (let i = 0; i + 1 < cuts.length; i++) {
        const out = at(`s${k}-${i}.film`);
        renderPart(cuts[i], cuts[i + 1], out, ['--threads', String(1 + ((i + k) % 3))]);
        parts.push(out);
      }
      parts.reverse();
      for (const ext of k === 0 ? ['film', 'pfm', 'png'] : ['film']) {
        pathwiseOk(['merge', ...parts, '--out', at(`m${k}.${ext}`)]);
        expect(same(at(`m${k}.${ext}`), at(`full.${ext}`)), `split ${cuts} .${ext}`).toBe(true);
      }
    });
    // The comparison can fail: a render with one sample fewer differs.
    pathwiseOk(['render', scene, '--spp', '11', '--out', at('short.pfm')]);
    expect(same(at('short.pfm'), at('full.pfm'))).toBe(false);
  });

  it('merges merged parts again (a hierarchy of merges)', () => {
    renderPart(0, 2, at('h0.film'));
    renderPart(2, 9, at('h1.film'));
    renderPart(9, 12, at('h2.film'));
    // An intermediate merge has gaps by design.
    pathwiseOk(['merge', at('h2.film'), at('h0.film'), '--out', at('h02.film'), '--allow-gaps']);
    expect(readFilm(at('h02.film')).header.ranges).toEqual([
      [0, 2],
      [9, 12],
    ]);
    const r = pathwiseOk(['merge', at('h1.film'), at('h02.film'), '--out', at('h.film'), '--json']);
    expect(same(at('h.film'), at('full.film'))).toBe(true);
    const json = JSON.parse(r.stdout);
    expect(json).toMatchObject({ parts: 2, spp: 12, total: 12, ranges: [[0, 12]], missing: [] });
    expect(json.noise).toBeGreaterThan(0);
  });

  it('records the identity, range and statistics in the part', () => {
    const { header, film } = readFilm(at('a.film'));
    expect(header.ranges).toEqual([[0, 6]]);
    expect(header.spp).toBe(SPP);
    expect(header.settings).toEqual({
      width: 24,
      height: 16,
      maxBounces: 6,
      seed: 0,
      sampler: 'sobol',
      estimator: 'nee-mis',
    });
    expect(header.scene_sha256).toMatch(/^[0-9a-f]{64}$/);
    expect(header.stats.paths).toBe(24 * 16 * 6);
    expect(film.sums[3]).toBe(6);
  });
});

describe('merge refuses', () => {
  it.each([
    ['another scene', [], /are renders of different scenes \(scene sha256/, true],
    ['another size', ['--width', '20'], /differ in image size \(24×16 and 20×16\)/, false],
    ['other bounces', ['--bounces', '3'], /differ in --bounces \(6 and 3\)/, false],
    ['another seed', ['--seed', '5'], /differ in --seed \(0 and 5\)/, false],
    [
      'another sampler',
      ['--sampler', 'independent'],
      /differ in --sampler \(sobol and independent\)/,
      false,
    ],
    [
      'another estimator',
      ['--estimator', 'bsdf'],
      /differ in --estimator \(nee-mis and bsdf\)/,
      false,
    ],
  ])('a part of %s', (what, extra, message, otherScene) => {
    const file = at(`x-${what.replace(/ /g, '-')}.film`);
    let source = scene;
    if (otherScene) {
      const s = JSON.parse(readFileSync(scene, 'utf8'));
      s.materials.white.albedo = [0.7, 0.7, 0.7];
      source = at('other-scene.json');
      writeFileSync(source, JSON.stringify(s));
    }
    pathwiseOk([
      'render',
      source,
      '--spp',
      String(SPP),
      '--samples',
      '6:12',
      '--out',
      file,
      ...extra,
    ]);
    expectRefusal(
      pathwise(['merge', at('a.film'), file, '--out', at('x.pfm')]),
      new RegExp(`cannot merge: a.film and x-.* ${message.source}`),
    );
  });

  it('the same scene written differently is the same scene', () => {
    const s = JSON.parse(readFileSync(scene, 'utf8'));
    s.name = 'renamed';
    s.settings.spp = 999; // settings change no pixel (the command line gives the total)
    const source = at('reformatted.json');
    writeFileSync(source, JSON.stringify(s));
    pathwiseOk([
      'render',
      source,
      '--spp',
      String(SPP),
      '--samples',
      '6:12',
      '--out',
      at('b2.film'),
    ]);
    pathwiseOk(['merge', at('a.film'), at('b2.film'), '--out', at('b2.pfm')]);
    expect(same(at('b2.pfm'), at('full.pfm'))).toBe(true);
  });

  it('a part of another renderer version', () => {
    const { header, film } = readFilm(at('b.film'));
    writeFileSync(at('old.film'), encodeFilmFile({ ...header, renderer: 'pathwise 0.0.9' }, film));
    expectRefusal(
      pathwise(['merge', at('a.film'), at('old.film'), '--out', at('x.pfm')]),
      /cannot merge: a.film and old.film come from different renderers \(pathwise 0\.1\.0 and pathwise 0\.0\.9\)/,
    );
  });

  it('overlapping ranges, and one part given twice', () => {
    renderPart(4, 12, at('c.film'));
    expectRefusal(
      pathwise(['merge', at('a.film'), at('c.film'), '--out', at('x.pfm')]),
      /cannot merge: a.film and c.film both hold samples \[4, 6\)/,
    );
    expectRefusal(
      pathwise(['merge', at('a.film'), at('b.film'), at('a.film'), '--out', at('x.pfm')]),
      /cannot merge: a.film and a.film both hold samples \[0, 6\)/,
    );
  });

  it('parts of renders with different totals, unless --spp chooses one', () => {
    pathwiseOk(['render', scene, '--spp', '24', '--samples', '6:12', '--out', at('t24.film')]);
    expectRefusal(
      pathwise(['merge', at('a.film'), at('t24.film'), '--out', at('x.pfm')]),
      /a.film is part of a 12-spp render and t24.film of a 24-spp one \(give --spp N/,
    );
    pathwiseOk(['merge', at('a.film'), at('t24.film'), '--spp', '12', '--out', at('t.pfm')]);
    expect(same(at('t.pfm'), at('full.pfm'))).toBe(true);
    expectRefusal(
      pathwise(['merge', at('a.film'), at('t24.film'), '--spp', '8', '--out', at('x.pfm')]),
      /t24.film holds samples \[6, 12\), beyond the total of 8/,
    );
  });

  it('missing ranges, naming them; --allow-gaps writes the partial result and says so', () => {
    renderPart(9, 11, at('g.film'));
    expectRefusal(
      pathwise(['merge', at('g.film'), at('a.film'), '--out', at('gap.pfm')]),
      /missing samples \[6, 9\) and \[11, 12\): the parts hold 8 of 12 samples per pixel .*--allow-gaps/,
    );
    const r = pathwise([
      'merge',
      at('g.film'),
      at('a.film'),
      '--out',
      at('gap.film'),
      '--allow-gaps',
      '--json',
    ]);
    expect(r.status).toBe(0);
    expect(r.stderr).toMatch(
      /warning: .*gap.film lacks samples \[6, 9\) and \[11, 12\): it holds 8 of 12/,
    );
    expect(JSON.parse(r.stdout)).toMatchObject({
      spp: 8,
      missing: [
        [6, 9],
        [11, 12],
      ],
    });
    // The partial film keeps its true ranges: the missing parts merge in later.
    expect(readFilm(at('gap.film')).header.ranges).toEqual([
      [0, 6],
      [9, 11],
    ]);
    renderPart(6, 9, at('g1.film'));
    renderPart(11, 12, at('g2.film'));
    pathwiseOk([
      'merge',
      at('gap.film'),
      at('g1.film'),
      at('g2.film'),
      '--out',
      at('gap-full.film'),
    ]);
    expect(same(at('gap-full.film'), at('full.film'))).toBe(true);
  });
});

describe('bad input', () => {
  it('a truncated part, a lying header, NaN inside, a non-film, a missing file: one line, exit 2', () => {
    const good = readFileSync(at('b.film'));
    writeFileSync(at('trunc.film'), good.subarray(0, good.length - 1000));
    expectRefusal(
      pathwise(['merge', at('a.film'), at('trunc.film'), '--out', at('x.pfm')]),
      /trunc.film: pathwise-film\/1: truncated: \d+ bytes, but a 24×16 film needs \d+/,
    );
    const { header, film } = readFilm(at('b.film'));
    writeFileSync(
      at('lying.film'),
      encodeFilmFile(
        { ...header, stats: { ...header.stats, paths: header.stats.paths + 1 } },
        film,
      ),
    );
    expectRefusal(
      pathwise(['merge', at('a.film'), at('lying.film'), '--out', at('x.pfm')]),
      /lying.film: pathwise-film\/1: stats do not add up/,
    );
    film.hi[40] = NaN;
    writeFileSync(at('nan.film'), encodeFilmFile(header, film));
    expectRefusal(
      pathwise(['merge', at('a.film'), at('nan.film'), '--out', at('x.pfm')]),
      /nan.film: pathwise-film\/1: pixel \(10, 0\) channel R: invalid exact sum \(NaN/,
    );
    writeFileSync(at('image.film'), readFileSync(at('full.pfm')));
    expectRefusal(
      pathwise(['merge', at('image.film'), '--out', at('x.pfm')]),
      /image.film: pathwise-film\/1: not a .film file/,
    );
    expectRefusal(
      pathwise(['merge', at('nope.film'), '--out', at('x.pfm')]),
      /cannot read .*nope.film: no such file or directory/,
    );
    expect(spawnSync('mkfifo', [at('pipe.film')]).status).toBe(0);
    expectRefusal(
      pathwise(['merge', at('pipe.film'), '--out', at('x.pfm')]),
      /cannot read .*pipe.film: not a regular file/,
    );
    mkdirSync(at('folder.film'));
    expectRefusal(
      pathwise(['merge', at('folder.film'), '--out', at('x.pfm')]),
      /cannot read .*folder.film: it is a directory/,
    );
    expectRefusal(
      pathwise([
        'render',
        scene,
        '--resume',
        at('nan.film'),
        '--samples',
        '6:12',
        '--out',
        at('x.pfm'),
      ]),
      /nan.film: pathwise-film\/1: pixel \(10, 0\)/,
    );
  });

  it.each([
    [
      ['render', 'S', '--samples', '5', '--out', 'x.film'],
      /--samples must be A:B with integers 0 <= A < B, got "5"/,
    ],
    [['render', 'S', '--samples', '6:6', '--out', 'x.film'], /--samples must be A:B/],
    [['render', 'S', '--samples', '-1:4', '--out', 'x.film'], /--samples must be A:B/],
    [
      ['render', 'S', '--samples', '0:13', '--out', 'x.film'],
      /--samples 0:13 goes past the render's 12 samples per pixel/,
    ],
    [
      ['render', 'S', '--time', '0', '--out', 'x.pfm'],
      /--time must be a decimal number > 0, got "0"/,
    ],
    [
      ['render', 'S', '--noise', 'low', '--out', 'x.pfm'],
      /--noise must be a decimal number > 0, got "low"/,
    ],
    [['render', 'S', '--checkpoint', 'c.pfm', '--out', 'x.pfm'], /--checkpoint must end in .film/],
    [
      ['render', 'S', '--checkpoint-every', '5', '--out', 'x.pfm'],
      /--checkpoint-every needs --checkpoint/,
    ],
    [
      ['render', 'S', '--out', '/nonexistent-dir/x.pfm'],
      /cannot write \/nonexistent-dir\/x.pfm: the directory \/nonexistent-dir does not exist/,
    ],
    [['merge', '--out', 'x.pfm'], /merge needs at least one PART.film/],
    [['merge', 'a.pfm', '--out', 'x.pfm'], /parts must be .film files/],
    [['merge', 'a.film', '--out', 'x.jpg'], /--out must end in .pfm, .png or .film/],
    [['merge', 'a.film', '--out', 'x.pfm', '--seed', '1'], /unknown option --seed/],
  ])('%j: one line, exit 2', (args, message) => {
    expectRefusal(
      pathwise(args.map((a) => (a === 'S' ? scene : a === 'x.film' || a === 'x.pfm' ? at(a) : a))),
      message,
    );
  });
});
