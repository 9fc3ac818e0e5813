/**
 * Independent references for the generator's mesh family (issue 11 §5):
 * triangle meshes (inline, OBJ and PLY; shading normals; mirroring and
 * extreme transforms; emissive meshes) and environment maps (constant,
 * gradient, sun; rotated and scaled; .hdr and .pfm), pathwise against
 * Mitsuba 3. The native anchor renders spheres and quads under a constant
 * environment only, so these scenes have one reference; the consistency
 * suite's mesh scenes (consistency-c.test.ts) check the same code with no
 * reference at all. The tests and their false-alarm rate are in
 * reference-check.ts.
 */
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { MESH_FEATURES } from './builder.ts';
import { coverage, manifest, names, referenceSuite } from './reference-check.ts';

const DIR = fileURLToPath(new URL('./references/', import.meta.url));
const mesh = names.filter((n) => coverage[n]?.family === 'mesh');

describe('the mesh reference set', () => {
  it('has at least 15 scenes with their files, rendered by Mitsuba, covering every mesh feature', () => {
    expect(mesh.length).toBeGreaterThanOrEqual(15);
    for (const n of mesh) {
      expect(manifest[n].mitsuba.sppPerPart, n).toBeGreaterThan(0);
      for (const f of coverage[n].files ?? []) expect(existsSync(`${DIR}${f}`), f).toBe(true);
    }
    const features = new Set(mesh.flatMap((n) => coverage[n].features ?? []));
    for (const f of MESH_FEATURES) expect(features.has(f), f).toBe(true);
  });
});

referenceSuite(mesh);
