/**
 * `pathwise render` of models whose textures use EXT_texture_webp or
 * KHR_texture_basisu (required, no fallback): the bundled command line reaches
 * libwebp and the vendored Basis Universal transcoder at run time and renders the
 * textured quad finite and not blank; a lying KTX2 header is one line naming the image.
 */
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { EXTTextureWebP, KHRTextureBasisu } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { docWith, quadPrimitive, toGlb } from '../helpers/gltf.ts';
import { ROOT } from '../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-compressed-'));
const bin = join(ROOT, 'bin/pathwise.js');
const fixture = (name: string) =>
  new Uint8Array(readFileSync(join(ROOT, 'tests/fixtures/compressed-textures', name)));

function run(args: string[]) {
  const r = spawnSync(process.execPath, [bin, ...args], { cwd: dir, encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

/** A quad whose base colour is `image`, through `ext` (required; glTF-Transform writes it). */
async function quad(image: Uint8Array, ext: 'webp' | 'ktx2'): Promise<Uint8Array> {
  const doc = new Document();
  if (ext === 'webp') doc.createExtension(EXTTextureWebP).setRequired(true);
  else doc.createExtension(KHRTextureBasisu).setRequired(true);
  const tex = doc.createTexture().setImage(image).setMimeType(`image/${ext}`);
  const mat = doc.createMaterial().setBaseColorTexture(tex).setMetallicFactor(0);
  return toGlb(docWith(doc, quadPrimitive(doc).setMaterial(mat)));
}

const small = ['--width', '24', '--height', '16', '--spp', '4'];

/** The rendered RGB at the centre, after checking every sample is finite. */
function centre(file: string): number[] {
  const img = decodePfm(readFileSync(join(dir, file)));
  expect(img.rgb.every(Number.isFinite)).toBe(true);
  const c = (8 * 24 + 12) * 3;
  return [img.rgb[c], img.rgb[c + 1], img.rgb[c + 2]];
}

describe('pathwise render with compressed textures', () => {
  it('EXT_texture_webp and KHR_texture_basisu (ETC1S and UASTC) render textured', async () => {
    writeFileSync(join(dir, 'webp.glb'), await quad(fixture('test-lossy.webp'), 'webp'));
    writeFileSync(join(dir, 'etc1s.glb'), await quad(fixture('2d_etc1s.ktx2'), 'ktx2'));
    writeFileSync(join(dir, 'uastc.glb'), await quad(fixture('2d_uastc.ktx2'), 'ktx2'));
    for (const name of ['webp', 'etc1s', 'uastc']) {
      const r = run(['render', `${name}.glb`, ...small, '--out', `${name}.pfm`]);
      expect(r.stderr).toBe('');
      expect(r.status).toBe(0);
      // Not blank: the textured quad against the studio backdrop (the WebP photo is
      // dark in the middle, sRGB about 50: the centre is dim but lit).
      expect(Math.max(...centre(`${name}.pfm`))).toBeGreaterThan(0.005);
      const { rgb } = decodePfm(readFileSync(join(dir, `${name}.pfm`)));
      expect(Math.max(...rgb) - Math.min(...rgb)).toBeGreaterThan(0.05);
    }
    // The KTX2 image is a gold ground (sRGB 186, 151, 0) with white marks: at the
    // centre, red well over blue (white alone would give them equal).
    for (const name of ['etc1s', 'uastc']) {
      const [r, , b] = centre(`${name}.pfm`);
      expect(r).toBeGreaterThan(1.5 * b);
    }
  });

  it('a KTX2 header that lies about its size: one line naming the image, status 2', async () => {
    const bytes = fixture('2d_uastc.ktx2');
    new DataView(bytes.buffer).setUint32(20, 16384, true);
    new DataView(bytes.buffer).setUint32(24, 16384, true);
    writeFileSync(join(dir, 'lying.glb'), await quad(bytes, 'ktx2'));
    const r = run(['render', 'lying.glb', ...small, '--out', 'lying.pfm']);
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(
      /^pathwise: lying\.glb: glTF: images\[0\] \(materials\[0\]\.baseColorTexture\): cannot decode KTX2: level 0 \(16384×16384\) declares 1600 bytes/,
    );
    expect(r.stderr.trim().split('\n').length).toBe(1);
  });
});
