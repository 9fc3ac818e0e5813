/**
 * `pathwise render` of meshopt- and Draco-compressed models (tests/fixtures/compressed):
 * each renders finite and not blank (the model covers part of the frame: pixels differ
 * from the studio backdrop seen in the corner), the decoders being loaded at run time
 * from node_modules, outside the bundle; a hostile compressed file is one line naming
 * the place in the file, exit status 2.
 */
import { spawnSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { ROOT } from '../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-compressed-'));
const bin = join(ROOT, 'bin/pathwise.js');
const FIXTURES = join(ROOT, 'tests/fixtures/compressed');

function run(args: string[]) {
  const r = spawnSync(process.execPath, [bin, ...args], { cwd: dir, encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

/** Fraction of pixels that differ from the corner's (the backdrop) by more than 0.02. */
function coverage(rgb: Float32Array, width: number, height: number): number {
  let n = 0;
  for (let p = 0; p < width * height; p++) {
    let d = 0;
    for (let k = 0; k < 3; k++) d = Math.max(d, Math.abs(rgb[3 * p + k] - rgb[k]));
    if (d > 0.02) n++;
  }
  return n / (width * height);
}

describe('pathwise render of compressed models', () => {
  for (const [file, what] of [
    ['Box.gltf', 'Draco (edgebreaker)'],
    ['DracoSparseMesh.gltf', 'Draco with a sparse accessor'],
    ['MorphPrimitivesTest.gltf', 'Draco with morph targets (rest pose)'],
    ['CesiumMilkTruck.gltf', 'Draco, several meshes, textured'],
    ['BoxMeshopt.glb', 'EXT_meshopt_compression, fallback buffer without a URI'],
    ['pirate.glb', 'EXT_meshopt_compression + KHR_mesh_quantization (gltfpack)'],
  ] as const) {
    it(`${file}: ${what}: finite, not blank`, () => {
      const out = join(dir, `${file}.pfm`);
      const r = run([
        'render',
        join(FIXTURES, file),
        '--width',
        '32',
        '--height',
        '32',
        '--spp',
        '2',
        '--threads',
        '1',
        '--out',
        out,
      ]);
      expect(r.status).toBe(0);
      expect(r.stderr).not.toMatch(/KHR_draco|meshopt/);
      const img = decodePfm(readFileSync(out));
      expect(img.rgb.every(Number.isFinite)).toBe(true);
      // The smallest of these covers 6 % of the frame at this size (DracoSparseMesh);
      // a model that did not load or decoded to nothing covers 0.
      expect(coverage(img.rgb, img.width, img.height)).toBeGreaterThan(0.02);
    });
  }

  it('a Draco stream that claims more than its accessors: one line naming it, exit 2', () => {
    const json = JSON.parse(readFileSync(join(FIXTURES, 'Box.gltf'), 'utf8'));
    json.accessors[0].count = 30;
    writeFileSync(join(dir, 'liar.gltf'), JSON.stringify(json));
    copyFileSync(join(FIXTURES, 'Box.bin'), join(dir, 'Box.bin'));
    const r = run(['render', 'liar.gltf', '--spp', '1', '--out', 'x.pfm']);
    expect(r.status).toBe(2);
    expect(r.stderr).toBe(
      'pathwise: liar.gltf: glTF: meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: ' +
        'the Draco stream declares 12 triangles, more than the 10 of its indices accessor\n',
    );
  });
});
