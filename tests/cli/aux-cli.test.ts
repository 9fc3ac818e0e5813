/**
 * `--albedo`, `--normal` and `--aux` (docs/film-format.md, "Albedo and normal"): the
 * images are bit-identical for any thread count and stripe layout, split renders merged
 * give the bytes of one run (the `.film` and both images), the radiance is the one of a
 * render without them, and parts with and without aux are refused with one line.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { ROOT } from '../helpers/render.ts';
import { expectRefusal, pathwise, pathwiseOk, readFilm, tempDir } from '../helpers/batch-cli.ts';

const dir = tempDir('aux');
const at = (name: string) => join(dir, name);
const SPP = 6;
let scene: string;

function same(a: string, b: string): boolean {
  return readFileSync(a).equals(readFileSync(b));
}

beforeAll(() => {
  // The mirror scene: diffuse walls, a light, a mirror sphere and a glass sphere.
  const s = JSON.parse(readFileSync(join(ROOT, 'scenes/mirror.json'), 'utf8'));
  s.settings = { ...s.settings, width: 20, height: 16, spp: SPP };
  scene = at('mirror.json');
  writeFileSync(scene, JSON.stringify(s));
  pathwiseOk([
    'render',
    scene,
    '--threads',
    '2',
    '--out',
    at('full.film'),
    '--albedo',
    at('albedo.pfm'),
    '--normal',
    at('normal.pfm'),
  ]);
});

describe('render --albedo --normal', () => {
  it('writes the same bytes for any thread count and stripe layout', () => {
    for (const [threads, rows] of [
      ['1', '16'],
      ['3', '1'],
    ]) {
      pathwiseOk([
        'render',
        scene,
        '--threads',
        threads,
        '--stripe-rows',
        rows,
        '--out',
        at(`t${threads}.pfm`),
        '--albedo',
        at(`a${threads}.pfm`),
        '--normal',
        at(`n${threads}.pfm`),
      ]);
      expect(same(at(`a${threads}.pfm`), at('albedo.pfm')), `albedo, ${threads} threads`).toBe(
        true,
      );
      expect(same(at(`n${threads}.pfm`), at('normal.pfm')), `normal, ${threads} threads`).toBe(
        true,
      );
    }
  });

  it('leaves the radiance as a render without them, and writes OIDN-ranged images', () => {
    pathwiseOk(['render', scene, '--out', at('plain.pfm')]);
    expect(same(at('plain.pfm'), at('t1.pfm'))).toBe(true);
    const albedo = decodePfm(readFileSync(at('albedo.pfm')));
    const normal = decodePfm(readFileSync(at('normal.pfm')));
    expect([albedo.width, albedo.height, normal.width, normal.height]).toEqual([20, 16, 20, 16]);
    for (const v of albedo.rgb) expect(v >= 0 && v <= 1).toBe(true);
    for (const v of normal.rgb) expect(v >= -1 && v <= 1).toBe(true);
    // Not blank: the walls' albedos and normals are there.
    expect(albedo.rgb.some((v) => v > 0.5)).toBe(true);
    expect(normal.rgb.some((v) => v < -0.9)).toBe(true);
  });

  it('worker threads killed mid-render: the aux planes too are finished from journals, same bytes', () => {
    const env = { ...process.env, PATHWISE_TEST_FAULTS: 'kill=2,crash=2,seed=3' };
    const r = pathwise(
      [
        'render',
        scene,
        '--threads',
        '2',
        '--stripe-rows',
        '2',
        '--out',
        at('faulty.film'),
        '--aux',
        '--json',
      ],
      ROOT,
      env,
    );
    expect(r.status, r.stderr).toBe(0);
    expect(JSON.parse(r.stdout).workers_replaced).toBeGreaterThanOrEqual(1);
    expect(same(at('faulty.film'), at('full.film'))).toBe(true);
  });

  it('a .film with aux is pathwise-film/2; without, pathwise-film/1 as before', () => {
    expect(readFilm(at('full.film')).header).toMatchObject({
      format: 'pathwise-film/2',
      aux: ['albedo', 'normal'],
    });
    pathwiseOk(['render', scene, '--out', at('plain.film')]);
    expect(readFilm(at('plain.film')).header.format).toBe('pathwise-film/1');
  });
});

describe('split and merge with aux', () => {
  it('parts rendered with --aux merge into the bytes of one run: film, albedo, normal', () => {
    const cuts = [0, 2, 5, SPP];
    const parts: string[] = [];
    for (let i = 0; i + 1 < cuts.length; i++) {
      const out = at(`p${i}.film`);
      pathwiseOk([
        'render',
        scene,
        '--samples',
        `${cuts[i]}:${cuts[i + 1]}`,
        '--threads',
        String(1 + (i % 2)),
        '--out',
        out,
        '--aux',
      ]);
      parts.push(out);
    }
    pathwiseOk([
      'merge',
      ...parts.reverse(),
      '--out',
      at('merged.film'),
      '--albedo',
      at('m-albedo.pfm'),
      '--normal',
      at('m-normal.pfm'),
    ]);
    expect(same(at('merged.film'), at('full.film'))).toBe(true);
    expect(same(at('m-albedo.pfm'), at('albedo.pfm'))).toBe(true);
    expect(same(at('m-normal.pfm'), at('normal.pfm'))).toBe(true);
    // The comparison can fail: one part fewer is another albedo.
    pathwiseOk([
      'merge',
      parts[0],
      parts[1],
      '--allow-gaps',
      '--out',
      at('gap.pfm'),
      '--albedo',
      at('gap-albedo.pfm'),
    ]);
    expect(same(at('gap-albedo.pfm'), at('albedo.pfm'))).toBe(false);
  });

  it('refuses to merge parts with and without aux, and aux images from parts without', () => {
    pathwiseOk(['render', scene, '--samples', '0:3', '--out', at('x0.film'), '--aux']);
    pathwiseOk(['render', scene, '--samples', '3:6', '--out', at('x1.film')]);
    expectRefusal(
      pathwise(['merge', at('x0.film'), at('x1.film'), '--out', at('x.pfm')]),
      /^pathwise: cannot merge: x0\.film holds albedo and normal \(pathwise-film\/2, rendered with --aux\) and x1\.film does not \(pathwise-film\/1\); render every part with --aux, or none$/,
    );
    expectRefusal(
      pathwise([
        'merge',
        at('x1.film'),
        '--allow-gaps',
        '--out',
        at('x.pfm'),
        '--normal',
        at('n.pfm'),
      ]),
      /cannot write --normal: the parts hold no albedo and normal \(render them with --aux\)/,
    );
  });

  it('a part with aux resumed (--resume) gives the bytes of one run', () => {
    pathwiseOk(['render', scene, '--samples', '0:2', '--out', at('c2.film'), '--aux']);
    pathwiseOk([
      'render',
      scene,
      '--resume',
      at('c2.film'),
      '--out',
      at('resumed.film'),
      '--albedo',
      at('resumed-albedo.pfm'),
    ]);
    expect(same(at('resumed.film'), at('full.film'))).toBe(true);
    expect(same(at('resumed-albedo.pfm'), at('albedo.pfm'))).toBe(true);
  });

  it('refuses to resume a checkpoint of the other kind', () => {
    pathwiseOk(['render', scene, '--samples', '0:3', '--out', at('c1.film')]);
    expectRefusal(
      pathwise(['render', scene, '--resume', at('c1.film'), '--out', at('r.pfm'), '--aux']),
      /cannot resume: .*c1\.film holds no albedo and normal/,
    );
    expectRefusal(
      pathwise(['render', scene, '--resume', at('x0.film'), '--out', at('r.pfm')]),
      /cannot resume: .*x0\.film holds albedo and normal .* add --aux/,
    );
  });
});

describe('the flags', () => {
  it('take .pfm files only, and are in the help', () => {
    expectRefusal(
      pathwise(['render', scene, '--out', at('o.pfm'), '--albedo', at('a.png')]),
      /--albedo must end in \.pfm/,
    );
    expectRefusal(pathwise(['render', scene, '--out', at('o.pfm'), '--aux=yes']), /--aux/);
    expectRefusal(
      pathwise(['render', scene, '--out', at('o.pfm'), '--albedo', at('o.pfm')]),
      /--albedo names the same file as --out/,
    );
    expectRefusal(
      pathwise(['merge', at('x0.film'), '--out', at('o.pfm'), '--normal', at('o.pfm')]),
      /--normal names the same file as --out/,
    );
    expectRefusal(
      pathwise([
        'render',
        scene,
        '--out',
        at('o.pfm'),
        '--albedo',
        at('an.pfm'),
        '--normal',
        at('an.pfm'),
      ]),
      /--albedo and --normal name the same file/,
    );
    const help = pathwise(['render', '--help']);
    expect(help.stdout + help.stderr).toMatch(/--albedo FILE\.pfm[\s\S]*--normal FILE\.pfm/);
    const mergeHelp = pathwise(['merge', '--help']);
    expect(mergeHelp.stdout).toMatch(/--albedo FILE\.pfm/);
  });
});
