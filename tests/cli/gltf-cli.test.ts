/**
 * `pathwise render` with glTF: a bare `.glb` or `.gltf` given instead of a scene file
 * (framed by its bounds, in the studio environment), a scene file with a `gltf` shape,
 * external buffers and images read relative to the model, warnings printed as notes,
 * renders bit-identical across thread counts, and a broken model as one line naming
 * the file, with exit status 2.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { KHRXMP } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { docWith, png, quadPrimitive, toGlb, toGltfFiles } from '../helpers/gltf.ts';
import { ROOT } from '../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-gltf-'));
const bin = join(ROOT, 'bin/pathwise.js');

function run(args: string[], cwd = dir) {
  const r = spawnSync(process.execPath, [bin, ...args], { cwd, encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

/** A textured quad (a red-and-green checker), red metal, in one document. */
function model(): Document {
  const doc = new Document();
  const tex = doc
    .createTexture()
    .setImage(png(2, 2, (x, y) => ((x + y) % 2 ? [200, 30, 30, 255] : [30, 200, 30, 255])))
    .setMimeType('image/png');
  const mat = doc.createMaterial().setBaseColorTexture(tex).setMetallicFactor(0.2);
  return docWith(doc, quadPrimitive(doc).setMaterial(mat));
}

const small = ['--width', '24', '--height', '16', '--spp', '4'];

describe('pathwise render MODEL.glb', () => {
  it('renders a bare model: framed, lit by the studio, the same bits on 1 and 2 threads', async () => {
    writeFileSync(join(dir, 'quad.glb'), await toGlb(model()));
    const a = run(['render', 'quad.glb', ...small, '--threads', '1', '--out', 'a.pfm']);
    const b = run(['render', 'quad.glb', ...small, '--threads', '2', '--out', 'b.pfm']);
    expect(a.stderr).toBe('');
    expect(a.status).toBe(0);
    expect(b.status).toBe(0);
    expect(readFileSync(join(dir, 'a.pfm')).equals(readFileSync(join(dir, 'b.pfm')))).toBe(true);
    const img = decodePfm(readFileSync(join(dir, 'a.pfm')));
    expect([img.width, img.height]).toEqual([24, 16]);
    // The quad fills the middle of the frame (framing), the studio lights it: the
    // centre is neither black nor the backdrop's grey.
    const c = ((8 * 24 + 12) * 3) as number;
    const centre = [img.rgb[c], img.rgb[c + 1], img.rgb[c + 2]];
    expect(Math.max(...centre)).toBeGreaterThan(0.05);
    expect(run(['render', 'quad.glb', ...small, '--out', 'q.png']).status).toBe(0);
    expect(readFileSync(join(dir, 'q.png')).subarray(1, 4).toString()).toBe('PNG');
  });

  it('reads a .gltf with its buffer and image beside it, from any working directory', async () => {
    mkdirSync(join(dir, 'assets/tex'), { recursive: true });
    for (const [name, bytes] of await toGltfFiles(model(), 'quad')) {
      writeFileSync(join(dir, 'assets', name), bytes);
    }
    const out = join(dir, 'g.pfm');
    const r = run(['render', join(dir, 'assets/quad.gltf'), ...small, '--out', out], tmpdir());
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
    // The same model as a GLB renders the same bits.
    run(['render', 'quad.glb', ...small, '--out', 'same.pfm']);
    expect(readFileSync(out).equals(readFileSync(join(dir, 'same.pfm')))).toBe(true);
  });

  it('a scene file can hold the model as a gltf shape', async () => {
    writeFileSync(join(dir, 'quad.glb'), await toGlb(model()));
    writeFileSync(
      join(dir, 'scene.json'),
      JSON.stringify({
        format: 'pathwise-scene/1',
        camera: { position: [0.5, 0.5, 3], target: [0.5, 0.5, 0], up: [0, 1, 0], fovY: 30 },
        materials: {},
        shapes: [{ type: 'gltf', file: 'quad.glb' }],
        environment: [1, 1, 1],
      }),
    );
    const r = run(['render', 'scene.json', ...small, '--json', '--out', 's.pfm']);
    expect(r.stderr).toBe('');
    expect(r.status).toBe(0);
  });

  it('prints what the file uses and pathwise ignores as notes', async () => {
    const doc = model();
    const xmp = doc
      .createExtension(KHRXMP)
      .createPacket()
      .setContext({ dc: 'http://purl.org/dc/elements/1.1/' });
    doc.getRoot().listMaterials()[0].setExtension('KHR_xmp_json_ld', xmp);
    writeFileSync(join(dir, 'coat.glb'), await toGlb(doc));
    const r = run(['render', 'coat.glb', ...small, '--out', 'c.pfm']);
    expect(r.status).toBe(0);
    expect(r.stderr).toBe(
      'pathwise: note: shapes[0] (coat.glb): extension "KHR_xmp_json_ld" is not supported; its content is ignored\n',
    );
  });

  it('textures over the memory limit: one line naming the image, before anything is decoded', async () => {
    // A PNG whose header claims 16384 × 16384 texels (2 GiB decoded at 8 bytes each,
    // over the 1 GiB limit) in a few dozen bytes: the limit is checked from the header.
    const ihdr = Buffer.alloc(25);
    ihdr.writeUInt32BE(13, 0);
    ihdr.write('IHDR', 4, 'latin1');
    ihdr.writeUInt32BE(16384, 8);
    ihdr.writeUInt32BE(16384, 12);
    ihdr.set([8, 6, 0, 0, 0], 16);
    const huge = Buffer.concat([
      Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
      ihdr,
    ]);
    const doc = new Document();
    const tex = doc.createTexture().setImage(huge).setMimeType('image/png');
    docWith(doc, quadPrimitive(doc).setMaterial(doc.createMaterial().setBaseColorTexture(tex)));
    writeFileSync(join(dir, 'huge.glb'), await toGlb(doc));
    const r = run(['render', 'huge.glb', '--spp', '1', '--out', 'x.pfm']);
    expect(r.status).toBe(2);
    expect(r.stderr.split('\n').length).toBe(2);
    expect(r.stderr).toBe(
      'pathwise: huge.glb: glTF: images[0] (materials[0].baseColorTexture): decoded textures ' +
        'would need 2.00 GiB, over the texture memory limit of 1.00 GiB\n',
    );
  });

  it('a broken model is one line naming the file, exit status 2', async () => {
    const glb = await toGlb(model());
    writeFileSync(join(dir, 'cut.glb'), glb.subarray(0, glb.length - 100));
    const r = run(['render', 'cut.glb', '--spp', '1', '--out', 'x.pfm']);
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(
      /^pathwise: cut\.glb: glTF: GLB header: says \d+ bytes, but the file has \d+/,
    );
    expect(r.stderr.split('\n').length).toBe(2);
    writeFileSync(
      join(dir, 'lonely.gltf'),
      JSON.stringify({ asset: { version: '2.0' }, buffers: [{ uri: 'gone.bin', byteLength: 4 }] }),
    );
    const m = run(['render', 'lonely.gltf', '--spp', '1', '--out', 'x.pfm']);
    expect(m.status).toBe(2);
    expect(m.stderr).toMatch(
      /^pathwise: lonely\.gltf: glTF: buffers\[0\]\.uri: cannot read "gone\.bin"/,
    );
  });
});
