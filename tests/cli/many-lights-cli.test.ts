/**
 * The light BVH keeps renders deterministic (issue 23): on a hall of 400 small lamps,
 * where every light sample goes through the BVH, `pathwise render` gives the same bytes
 * with 1 and 2 threads, and parts split anywhere and merged give the bytes of one run.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { pathwiseOk, tempDir } from '../helpers/batch-cli.ts';
import { manyLights } from '../helpers/many-lights-scene.mjs';

const dir = tempDir('many-lights');
const at = (name: string) => join(dir, name);
const size = ['--width', '24', '--height', '16', '--spp', '6'];

describe('many lights on the command line', () => {
  it('give the same bytes for any thread count and any split', () => {
    const scene = at('hall.json');
    writeFileSync(scene, JSON.stringify(manyLights(400)));
    pathwiseOk(['render', scene, ...size, '--threads', '1', '--out', at('one.film')]);
    pathwiseOk(['render', scene, ...size, '--threads', '2', '--out', at('two.film')]);
    pathwiseOk(['render', scene, ...size, '--samples', '0:1', '--out', at('a.film')]);
    pathwiseOk([
      'render',
      scene,
      ...size,
      '--samples',
      '1:6',
      '--threads',
      '2',
      '--out',
      at('b.film'),
    ]);
    pathwiseOk(['merge', at('b.film'), at('a.film'), '--out', at('merged.film')]);
    const one = readFileSync(at('one.film'));
    expect(readFileSync(at('two.film')).equals(one)).toBe(true);
    expect(readFileSync(at('merged.film')).equals(one)).toBe(true);
  });
});
