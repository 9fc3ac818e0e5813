/**
 * Adaptive sampling on the command line (issue 23, deliverable 2;
 * src/core/film/adaptive.ts): each pixel holds exactly the samples the rule gives
 * for the map built from the uniform pilot; the bytes are the same for any thread
 * count, any split into parts merged in any order, and a resume past the pilot; the
 * film says it is adaptive, and parts of an adaptive and a uniform render never merge.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import {
  ADAPTIVE_PILOT,
  RATE_ONE,
  adaptiveCount,
  buildSampleMap,
} from '../../src/core/film/adaptive.ts';
import { encodeFilmFile } from '../../src/core/index.ts';
import {
  expectRefusal,
  pathwise,
  pathwiseOk,
  readFilm,
  tempDir,
  writeCornell,
} from '../helpers/batch-cli.ts';

const dir = tempDir('adaptive');
const at = (name: string) => join(dir, name);
const W = 40;
const H = 30;
const SPP = 80;
const scene = writeCornell(dir, { width: W, height: H, spp: SPP });
const render = (...args: string[]) => pathwiseOk(['render', scene, ...args]);

describe('adaptive sampling on the command line', () => {
  it('gives each pixel the samples of its rate in the map of the uniform pilot', () => {
    const json = JSON.parse(
      render('--adaptive', 'on', '--out', at('whole.film'), '--json', '--threads', '2').stdout,
    );
    // The pilot of an adaptive render is the uniform render of its first passes.
    render('--samples', `0:${ADAPTIVE_PILOT}`, '--out', at('pilot.film'));
    const map = buildSampleMap(readFilm(at('pilot.film')).film, new Uint8Array(W * H));
    const { header, film } = readFilm(at('whole.film'));
    expect(header.settings.adaptive).toBe(true);
    expect(header.stats.rejected).toBe(0);
    let total = 0;
    for (let p = 0; p < W * H; p++) {
      const expected = adaptiveCount(SPP, ADAPTIVE_PILOT, map[p]);
      if (film.sums[p * 4 + 3] !== expected) {
        throw new Error(`pixel ${p}: ${film.sums[p * 4 + 3]} samples, the rule gives ${expected}`);
      }
      total += expected;
    }
    expect(json.paths).toBe(total);
    // The box has smooth and noisy parts: the map is not uniform, and saves samples.
    expect(new Set(map).size).toBeGreaterThan(4);
    expect(map.some((k) => k === RATE_ONE)).toBe(true);
    expect(total).toBeLessThan(0.8 * W * H * SPP);
  });

  it('gives the same bytes for any thread count, split, order and resume', () => {
    render('--adaptive', 'on', '--threads', '1', '--out', at('one.film'));
    const one = readFileSync(at('one.film'));
    expect(readFileSync(at('whole.film')).equals(one)).toBe(true);
    // Parts inside the pilot, across its end, and past it (these render the pilot apart).
    render('--adaptive', 'on', '--samples', '0:7', '--out', at('a.film'));
    render('--adaptive', 'on', '--samples', '7:30', '--out', at('b.film'), '--threads', '1');
    render('--adaptive', 'on', '--samples', '30:80', '--out', at('c.film'));
    pathwiseOk(['merge', at('c.film'), at('a.film'), at('b.film'), '--out', at('merged.film')]);
    expect(readFileSync(at('merged.film')).equals(one)).toBe(true);
    // A part past the pilot given the pilot (--samples 0:16 of the same render) to read
    // instead of rendering it: the same bytes and counters (a pilot rendered apart is not
    // counted either).
    render('--adaptive', 'on', '--samples', '0:16', '--out', at('pilot16.film'));
    const own = JSON.parse(
      render('--adaptive', 'on', '--samples', '30:80', '--out', at('c2.film'), '--json').stdout,
    );
    const given = JSON.parse(
      render(
        ...['--adaptive', 'on', '--samples', '30:80', '--pilot', at('pilot16.film')],
        ...['--out', at('c3.film'), '--json'],
      ).stdout,
    );
    expect(readFileSync(at('c3.film')).equals(readFileSync(at('c.film')))).toBe(true);
    expect(given.paths).toBe(own.paths);
    expect(given.segments).toBe(own.segments);
    // With albedo and normal planes (the denoiser's guides), split across the pilot's end.
    render('--adaptive', 'on', '--aux', '--out', at('aux.film'));
    render('--adaptive', 'on', '--aux', '--samples', '0:20', '--out', at('aux-a.film'));
    render('--adaptive', 'on', '--aux', '--samples', '20:80', '--out', at('aux-b.film'));
    pathwiseOk(['merge', at('aux-b.film'), at('aux-a.film'), '--out', at('aux-m.film')]);
    expect(readFileSync(at('aux-m.film')).equals(readFileSync(at('aux.film')))).toBe(true);
    // Resumed from a checkpoint inside the pilot, and from one past it.
    for (const cut of [9, 41]) {
      const ckpt = at(`ckpt-${cut}.film`);
      render('--adaptive', 'on', '--samples', `0:${cut}`, '--out', ckpt);
      render('--adaptive', 'on', '--resume', ckpt, '--checkpoint', ckpt, '--out', at('r.film'));
      expect(readFileSync(at('r.film')).equals(one), `resumed at ${cut}`).toBe(true);
    }
  });

  it('is on with --noise unless turned off, and off otherwise', () => {
    render('--noise', '0.1', '--out', at('noise.film'));
    expect(readFilm(at('noise.film')).header.settings.adaptive).toBe(true);
    render('--noise', '0.1', '--adaptive', 'off', '--out', at('noise-off.film'));
    expect(readFilm(at('noise-off.film')).header.settings).not.toHaveProperty('adaptive');
    render('--spp', '4', '--out', at('plain.film'));
    expect(readFilm(at('plain.film')).header.settings).not.toHaveProperty('adaptive');
  });

  it('refuses to merge adaptive and uniform parts, a bad --adaptive or --pilot, a lying header', () => {
    render('--samples', '30:80', '--out', at('uniform-c.film'));
    expectRefusal(
      pathwise(['merge', at('a.film'), at('b.film'), at('uniform-c.film'), '--out', at('x.film')]),
      /differ in --adaptive \(on and off\)/,
    );
    expectRefusal(
      pathwise(['render', scene, '--adaptive', 'maybe', '--out', at('x.pfm')]),
      /--adaptive must be on or off, got "maybe"/,
    );
    // --pilot: a film of another render, one that is not exactly the pilot, no adaptive.
    const part = ['render', scene, '--adaptive', 'on', '--samples', '30:80', '--out', at('z.film')];
    render('--adaptive', 'on', '--samples', '0:16', '--seed', '3', '--out', at('p-seed3.film'));
    expectRefusal(
      pathwise([...part, '--pilot', at('p-seed3.film')]),
      /cannot use the pilot: .*p-seed3\.film and this render differ in --seed \(3 and 0\)/,
    );
    expectRefusal(
      pathwise([...part, '--pilot', at('a.film')]),
      /cannot use the pilot: .*a\.film holds samples \[0, 7\), not the pilot \[0, 16\)/,
    );
    expectRefusal(
      pathwise(['render', scene, '--pilot', at('pilot16.film'), '--out', at('z.pfm')]),
      /--pilot is for adaptive sampling: add --adaptive on \(or --noise\)/,
    );
    // A header whose settings.adaptive is not `true` (re-encoded: the checksum is right).
    const { header, film } = readFilm(at('plain.film'));
    const lying = encodeFilmFile(
      { ...header, settings: { ...header.settings, adaptive: false as unknown as true } },
      film,
    );
    writeFileSync(at('lying.film'), lying);
    expectRefusal(
      pathwise(['merge', at('lying.film'), '--out', at('y.pfm')]),
      /settings\.adaptive must be true where present/,
    );
  });
});
