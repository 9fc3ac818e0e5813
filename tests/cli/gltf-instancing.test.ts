/**
 * Instanced glTF through the command line (docs/gltf.md, Instancing): the instances'
 * arrays travel to the workers in the packed scene, and a render is the same bits on
 * 1, 2 and 4 threads — SimpleInstancing (125 EXT_mesh_gpu_instancing rows) and
 * AttenuationTest (meshes shared by several nodes).
 */
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { ROOT } from '../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-instancing-'));
const bin = join(ROOT, 'bin/pathwise.js');

describe('pathwise render of instanced models', () => {
  for (const name of ['SimpleInstancing.glb', 'AttenuationTest.glb']) {
    it(`${name}: the same bits on 1, 2 and 4 threads`, () => {
      const films: Buffer[] = [];
      for (const threads of ['1', '2', '4']) {
        const out = join(dir, `${name}-${threads}.pfm`);
        const r = spawnSync(
          process.execPath,
          [
            bin,
            'render',
            join(ROOT, 'tests/fixtures/gltf-instancing', name),
            '--width',
            '24',
            '--height',
            '16',
            '--spp',
            '4',
            '--threads',
            threads,
            '--out',
            out,
          ],
          { encoding: 'utf8' },
        );
        expect(r.status, r.stderr).toBe(0);
        films.push(readFileSync(out));
      }
      expect(films[1].equals(films[0])).toBe(true);
      expect(films[2].equals(films[0])).toBe(true);
      const img = decodePfm(films[0]);
      let lit = 0;
      for (const v of img.rgb) {
        expect(Number.isFinite(v)).toBe(true);
        if (v > 0) lit++;
      }
      expect(lit).toBeGreaterThan(img.rgb.length / 2);
    });
  }
});
