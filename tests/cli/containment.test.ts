/**
 * `pathwise render` keeps a model's files beside it (issue 27, finding 6): a `.gltf`
 * whose buffer or image climbs out of its folder with `..`, names /etc/passwd, or
 * reaches out through a link fails with one line and exit 2, before any byte of the
 * outside file is used; `--allow-read DIR` lets a model read a sibling folder of
 * textures, and a scene's folder holds the models and textures under it.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { describe, expect, it } from 'vitest';
import { docWith, png, quadPrimitive, toGltfFiles } from '../helpers/gltf.ts';
import { ROOT } from '../helpers/render.ts';

const bin = join(ROOT, 'bin/pathwise.js');
const small = ['--width', '8', '--height', '8', '--spp', '1'];

function run(args: string[], cwd: string) {
  const r = spawnSync(process.execPath, [bin, ...args], { cwd, encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

/**
 * A textured quad as `name.gltf` in `dir/folder`, its buffer and image at the URIs
 * given (relative to the model), their bytes written where `place` says (relative to
 * `dir`).
 */
async function writeModel(
  dir: string,
  folder: string,
  uris: { buffer: string; image: string },
  place: { buffer: string; image: string },
): Promise<void> {
  const doc = new Document();
  const tex = doc
    .createTexture()
    .setImage(png(2, 2, () => [200, 30, 30, 255]))
    .setMimeType('image/png');
  const mat = doc.createMaterial().setBaseColorTexture(tex);
  const files = await toGltfFiles(docWith(doc, quadPrimitive(doc).setMaterial(mat)), 'quad');
  const json = JSON.parse(new TextDecoder().decode(files.get('quad.gltf')!));
  const buffer = files.get(decodeURIComponent(json.buffers[0].uri))!;
  const image = files.get(decodeURIComponent(json.images[0].uri))!;
  json.buffers[0].uri = uris.buffer;
  json.images[0].uri = uris.image;
  mkdirSync(join(dir, folder), { recursive: true });
  writeFileSync(join(dir, folder, 'quad.gltf'), JSON.stringify(json));
  for (const [path, bytes] of [
    [place.buffer, buffer],
    [place.image, image],
  ] as const) {
    mkdirSync(join(dir, path, '..'), { recursive: true });
    writeFileSync(join(dir, path), bytes);
  }
}

function expectRefused(r: ReturnType<typeof run>, pattern: RegExp): void {
  expect(r.status).toBe(2);
  const lines = r.stderr.trimEnd().split('\n');
  expect(lines).toHaveLength(1);
  expect(lines[0]).toMatch(pattern);
}

describe('pathwise render: a model reads only files beside it', () => {
  it('refuses ../outside.bin and ../outside.png with one line, exit 2', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-contain-cli-'));
    await writeModel(
      dir,
      'm',
      { buffer: '../outside.bin', image: 'quad.png' },
      { buffer: 'outside.bin', image: 'm/quad.png' },
    );
    expectRefused(
      run(['render', 'm/quad.gltf', ...small, '--out', 'a.pfm'], dir),
      /^pathwise: .*buffers\[0\]\.uri: "\.\.\/outside\.bin" resolves to "\.\.\/outside\.bin", outside the model's folder and the scene's/,
    );
    await writeModel(
      dir,
      'n',
      { buffer: 'quad.bin', image: '../outside.png' },
      { buffer: 'n/quad.bin', image: 'outside.png' },
    );
    expectRefused(
      run(['render', 'n/quad.gltf', ...small, '--out', 'b.pfm'], dir),
      /images\[0\]\.uri: "\.\.\/outside\.png" resolves to "\.\.\/outside\.png", outside/,
    );
  });

  it('refuses /etc/passwd reached by .., and shows none of its bytes', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-contain-cli-'));
    const climb = '../'.repeat(30) + 'etc/passwd';
    await writeModel(
      dir,
      'm',
      { buffer: climb, image: 'quad.png' },
      { buffer: 'm/unused.bin', image: 'm/quad.png' },
    );
    const r = run(['render', 'm/quad.gltf', ...small, '--out', 'a.pfm'], dir);
    expectRefused(r, /buffers\[0\]\.uri: .* outside the model's folder/);
    expect(r.stderr).not.toMatch(/root:/);
  });

  it('refuses a link in the model folder that points out', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-contain-cli-'));
    await writeModel(
      dir,
      'm',
      { buffer: 'quad.bin', image: 'quad.png' },
      { buffer: 'secret/quad.bin', image: 'm/quad.png' },
    );
    symlinkSync(join(dir, 'secret/quad.bin'), join(dir, 'm/quad.bin'));
    expectRefused(
      run(['render', 'm/quad.gltf', ...small, '--out', 'a.pfm'], dir),
      /buffers\[0\]\.uri: cannot read "quad\.bin": the file lies outside the scene's folder \(through a link, to .*secret\/quad\.bin\)/,
    );
  });

  it('a texture folder beside the model folder: inside a scene, or with --allow-read', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-contain-cli-'));
    await writeModel(
      dir,
      'models/car',
      { buffer: 'quad.bin', image: '../textures/quad.png' },
      { buffer: 'models/car/quad.bin', image: 'models/textures/quad.png' },
    );
    // Rendered alone, the model's folder is models/car: the texture is outside.
    expectRefused(
      run(['render', 'models/car/quad.gltf', ...small, '--out', 'a.pfm'], dir),
      /images\[0\]\.uri: .* outside the model's folder/,
    );
    const allowed = run(
      [
        'render',
        'models/car/quad.gltf',
        ...small,
        '--allow-read',
        'models/textures',
        '--out',
        'b.pfm',
      ],
      dir,
    );
    expect(allowed.stderr).toBe('');
    expect(allowed.status).toBe(0);
    // A scene in the folder above names the model: its folder holds the textures.
    writeFileSync(
      join(dir, 'scene.json'),
      JSON.stringify({
        format: 'pathwise-scene/1',
        camera: { position: [0.5, 0.5, 3], target: [0.5, 0.5, 0], up: [0, 1, 0], fovY: 30 },
        materials: {},
        shapes: [{ type: 'gltf', file: 'models/car/quad.gltf' }],
        environment: [1, 1, 1],
      }),
    );
    const scene = run(['render', 'scene.json', ...small, '--out', 'c.pfm'], dir);
    expect(scene.stderr).toBe('');
    expect(scene.status).toBe(0);
  });

  it('a scene names files inside its folder, or in an --allow-read folder', () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-contain-cli-'));
    mkdirSync(join(dir, 'scenes'));
    mkdirSync(join(dir, 'meshes'));
    writeFileSync(join(dir, 'meshes/tri.obj'), 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n');
    writeFileSync(
      join(dir, 'scenes/s.json'),
      JSON.stringify({
        format: 'pathwise-scene/1',
        camera: { position: [0.3, 0.3, 3], target: [0.3, 0.3, 0], up: [0, 1, 0], fovY: 30 },
        materials: { m: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
        shapes: [{ type: 'mesh', material: 'm', file: '../meshes/tri.obj' }],
        environment: [1, 1, 1],
      }),
    );
    expectRefused(
      run(['render', 'scenes/s.json', ...small, '--out', 'a.pfm'], dir),
      /^pathwise: .*shapes\[0\]\.file "\.\.\/meshes\/tri\.obj": the file lies outside the scene's folder; .* --allow-read FOLDER/,
    );
    const r = run(
      ['render', 'scenes/s.json', ...small, '--allow-read', 'meshes', '--out', 'b.pfm'],
      dir,
    );
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
  });

  it('--allow-read needs a folder; --help names it', () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-contain-cli-'));
    expectRefused(
      run(['render', 'x.json', '--out', 'a.pfm', '--allow-read'], dir),
      /--allow-read needs a folder/,
    );
    expect(run(['render', '--help'], dir).stdout).toMatch(/--allow-read DIR/);
  });
});
