#!/usr/bin/env node
/**
 * Film digests: renders the canonical scenes, the 10,000-sphere field, the bunny room
 * and the showcase glTF model with the built command line (bin/pathwise.js, dist/cli)
 * at fixed sizes, samples and seeds, and prints the SHA-256 of each .film (its exact
 * sums, every plane) and PFM. A refactoring that changes no arithmetic leaves every
 * line the same: `node scripts/film-digests.mjs > before.txt`, change, rebuild, diff.
 */
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { spheresField } from '../bench/scenes.mjs';

const root = new URL('..', import.meta.url).pathname;
const cli = join(root, 'bin/pathwise.js');
const dir = mkdtempSync(join(tmpdir(), 'pathwise-digests-'));
const scenes = readdirSync(join(root, 'scenes'))
  .filter((f) => f.endsWith('.json'))
  .sort()
  .map((f) => [`scenes/${f}`, ['--width', '64', '--height', '48', '--spp', '4']]);
const field = join(dir, 'spheres-10k.json');
writeFileSync(field, JSON.stringify(spheresField(10000)));
const cases = [
  ...scenes,
  [field, ['--width', '96', '--height', '72', '--spp', '2', '--seed', '7']],
  ['scenes/spheres.json', ['--width', '96', '--height', '72', '--spp', '2', '--seed', '7']],
  ['docs/showcase.glb', ['--width', '64', '--height', '64', '--spp', '4']],
  ['scenes/cornell.json', ['--width', '48', '--height', '48', '--spp', '4', '--estimator', 'bsdf']],
  [
    'scenes/cornell.json',
    ['--width', '48', '--height', '48', '--spp', '4', '--sampler', 'independent'],
  ],
];
const sha = (file) => createHash('sha256').update(readFileSync(file)).digest('hex').slice(0, 16);
try {
  for (const [scene, args] of cases) {
    const film = join(dir, 'out.film');
    const pfm = join(dir, 'out.pfm');
    for (const out of [film, pfm]) {
      execFileSync(
        process.execPath,
        [
          cli,
          'render',
          scene.startsWith('/') ? scene : join(root, scene),
          '--out',
          out,
          '--threads',
          '2',
          ...args,
        ],
        {
          stdio: ['ignore', 'ignore', 'inherit'],
        },
      );
    }
    console.log(
      `${scene.replace(dir, '(tmp)')} ${args.join(' ')}  film ${sha(film)}  pfm ${sha(pfm)}`,
    );
  }
} finally {
  rmSync(dir, { recursive: true, force: true });
}
