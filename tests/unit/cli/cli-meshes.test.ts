/**
 * `pathwise render` with meshes and environment maps: files are read relative to the
 * scene file (whatever the working directory), renders stay bit-identical across
 * thread counts, zero-area triangles are reported, and a bad mesh file is one message
 * naming the shape, the file and the line, with exit status 2.
 */
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { ROOT } from '../../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-meshes-'));
const bin = join(ROOT, 'bin/pathwise.js');

function run(args: string[], cwd = dir) {
  const r = spawnSync(process.execPath, [bin, ...args], { cwd, encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

describe('pathwise render with mesh and map files', () => {
  it('reads them relative to the scene and renders the same bits on 1 and 2 threads', () => {
    const scene = join(ROOT, 'scenes/metal-sky.json');
    const small = ['--width', '24', '--height', '24', '--spp', '4'];
    const a = join(dir, 'a.pfm');
    const b = join(dir, 'b.pfm');
    execFileSync(process.execPath, [bin, 'render', scene, ...small, '--threads', '1', '--out', a], {
      cwd: dir,
    });
    execFileSync(process.execPath, [bin, 'render', scene, ...small, '--threads', '2', '--out', b], {
      cwd: dir,
    });
    expect(readFileSync(a).equals(readFileSync(b))).toBe(true);
  });

  it('reports zero-area triangles and rejects a bad file by shape, file and line', () => {
    mkdirSync(join(dir, 'm'), { recursive: true });
    writeFileSync(
      join(dir, 'm/flat.obj'),
      'v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n',
    );
    writeFileSync(join(dir, 'm/bad.obj'), 'v 0 0 0\nv 1 0 0\nf 1 2 7\n');
    const scene = (file: string) =>
      JSON.stringify({
        format: 'pathwise-scene/1',
        camera: { position: [0.5, 0.3, -3], target: [0.5, 0.3, 0], up: [0, 1, 0], fovY: 40 },
        materials: { m: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
        shapes: [{ type: 'mesh', material: 'm', file }],
        environment: [1, 1, 1],
      });
    writeFileSync(join(dir, 'flat.json'), scene('m/flat.obj'));
    writeFileSync(join(dir, 'bad.json'), scene('m/bad.obj'));
    const ok = run([
      'render',
      'flat.json',
      '--width',
      '8',
      '--height',
      '8',
      '--spp',
      '1',
      '--json',
      '--out',
      'f.pfm',
    ]);
    expect(ok.status).toBe(0);
    expect(ok.stderr).toContain('skipped 1 triangles of zero area');
    expect(JSON.parse(ok.stdout).skipped_triangles).toBe(1);
    const bad = run(['render', 'bad.json', '--spp', '1', '--out', 'b.pfm']);
    expect(bad.status).toBe(2);
    expect(bad.stderr.trim()).toBe(
      'pathwise: bad.json: shapes[0].file "m/bad.obj": OBJ: line 3: vertex index 7 is out of range: ' +
        'the file has 2 vertices',
    );
    writeFileSync(join(dir, 'missing.json'), scene('m/none.obj'));
    const missing = run(['render', 'missing.json', '--spp', '1', '--out', 'x.pfm']);
    expect(missing.status).toBe(2);
    expect(missing.stderr).toMatch(
      /^pathwise: missing\.json: shapes\[0\]\.file "m\/none\.obj": cannot read .*m\/none\.obj: no such file or directory\n$/,
    );
  });
});
