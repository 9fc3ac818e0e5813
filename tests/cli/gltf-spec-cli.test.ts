/**
 * KHR_materials_anisotropy and KHR_materials_iridescence end to end through
 * `pathwise render`: a real model (Khronos' AnisotropyStrengthTest, CC0, in
 * tests/fixtures/gltf) and generated spheres render finite, not blank, with no
 * "ignored" note for either extension; an anisotropic material without TANGENT
 * or normal map gets generated tangents; and the reductions render both ways:
 * strength 0 and iridescence 0 give the bits of the same model without the
 * extension, while strength 1 and a film change the image.
 */
import { spawnSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document, type Material } from '@gltf-transform/core';
import { KHRMaterialsAnisotropy, KHRMaterialsIridescence } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { docWith, meshPrimitive, toGlb } from '../helpers/gltf.ts';
import { ROOT } from '../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-spec-'));
const bin = join(ROOT, 'bin/pathwise.js');

function render(file: string, out: string, size = 24) {
  const r = spawnSync(
    process.execPath,
    [bin, 'render', file, '--width', `${size}`, '--height', `${size}`, '--spp', '4', '--out', out],
    { cwd: dir, encoding: 'utf8' },
  );
  return { status: r.status, stderr: r.stderr, pfm: readFileSync(join(dir, out)) };
}

/** Finite everywhere and not one flat value. */
function looksRendered(pfm: Uint8Array): void {
  const img = decodePfm(pfm);
  let min = Infinity;
  let max = -Infinity;
  for (const v of img.rgb) {
    expect(Number.isFinite(v)).toBe(true);
    min = Math.min(min, v);
    max = Math.max(max, v);
  }
  expect(max - min).toBeGreaterThan(0.05);
}

/** A UV sphere with normals and texture coordinates, no TANGENT. */
function sphere(doc: Document, material: Material) {
  const pos: number[] = [];
  const uv: number[] = [];
  const idx: number[] = [];
  const nt = 16;
  const np = 32;
  for (let i = 0; i <= nt; i++) {
    for (let j = 0; j <= np; j++) {
      const t = (Math.PI * i) / nt;
      const p = (2 * Math.PI * j) / np;
      pos.push(Math.sin(t) * Math.cos(p), Math.cos(t), Math.sin(t) * Math.sin(p));
      uv.push(j / np, i / nt);
    }
  }
  for (let i = 0; i < nt; i++) {
    for (let j = 0; j < np; j++) {
      const a = i * (np + 1) + j;
      const b = a + np + 1;
      // The poles' rows are points: one triangle of each quad there has no area.
      if (i > 0) idx.push(a, a + 1, b);
      if (i < nt - 1) idx.push(a + 1, b + 1, b);
    }
  }
  return meshPrimitive(doc, pos, idx, { normals: pos, uv }).setMaterial(material);
}

type Ext = 'none' | 'aniso0' | 'aniso1' | 'irid0' | 'irid1';

async function model(ext: Ext): Promise<string> {
  const doc = new Document();
  const mat = doc
    .createMaterial()
    .setBaseColorFactor([0.9, 0.7, 0.4, 1])
    .setMetallicFactor(1)
    .setRoughnessFactor(0.3);
  if (ext === 'aniso0' || ext === 'aniso1') {
    const a = doc
      .createExtension(KHRMaterialsAnisotropy)
      .createAnisotropy()
      .setAnisotropyStrength(ext === 'aniso1' ? 1 : 0)
      .setAnisotropyRotation(0.4);
    mat.setExtension('KHR_materials_anisotropy', a);
  }
  if (ext === 'irid0' || ext === 'irid1') {
    const i = doc
      .createExtension(KHRMaterialsIridescence)
      .createIridescence()
      .setIridescenceFactor(ext === 'irid1' ? 1 : 0)
      .setIridescenceIOR(1.8)
      .setIridescenceThicknessMaximum(350);
    mat.setExtension('KHR_materials_iridescence', i);
  }
  docWith(doc, sphere(doc, mat));
  const file = `${ext}.glb`;
  writeFileSync(join(dir, file), await toGlb(doc));
  return file;
}

describe('KHR_materials_anisotropy and KHR_materials_iridescence in the CLI', () => {
  it('AnisotropyStrengthTest.glb renders, finite and not blank, with nothing ignored', () => {
    copyFileSync(
      join(ROOT, 'tests/fixtures/gltf/AnisotropyStrengthTest.glb'),
      join(dir, 'strength.glb'),
    );
    const r = render('strength.glb', 'strength.pfm', 32);
    expect(r.status).toBe(0);
    expect(r.stderr).not.toMatch(/anisotropy|ignored/);
    looksRendered(r.pfm);
  });

  it('reductions render both ways: strength 0 and iridescence 0 are the plain model, bit for bit', async () => {
    const plain = render(await model('none'), 'none.pfm').pfm;
    for (const ext of ['aniso0', 'irid0'] as const) {
      const r = render(await model(ext), `${ext}.pfm`);
      expect(r.stderr).toBe('');
      expect(r.pfm.equals(plain), ext).toBe(true);
    }
    // …and the extensions do something: strength 1 (tangents generated: no
    // TANGENT, no normal map) and a 350 nm film change the image.
    for (const ext of ['aniso1', 'irid1'] as const) {
      const r = render(await model(ext), `${ext}.pfm`);
      expect(r.status).toBe(0);
      expect(r.stderr).toBe('');
      looksRendered(r.pfm);
      expect(r.pfm.equals(plain), ext).toBe(false);
    }
  });
});
