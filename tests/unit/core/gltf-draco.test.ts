/**
 * KHR_draco_mesh_compression (core/gltf/draco.ts, draco-header.ts) with draco3dgltf's
 * decoder: the sample files decode to the counts their accessors declare (a sparse
 * accessor over a Draco primitive included), the header's counts are read without
 * decoding, and a stream that claims more than its accessors, decodes to other counts,
 * or lacks an attribute gets one GltfError naming the primitive's extension. Loading a
 * file that uses no compression calls no decoder getter.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { nodeGltfDecoders } from '../../../src/cli/gltf-node.ts';
import { peekDracoCounts } from '../../../src/core/gltf/draco-header.ts';
import { GltfError } from '../../../src/core/gltf/errors.ts';
import { loadGltf, type GltfDecoders } from '../../../src/core/gltf/load.ts';
import { quadGlb } from '../../fuzz/gltf-samples.ts';
import { memoryOptions } from '../../helpers/gltf.ts';
import { meshoptQuadGlb } from '../../helpers/meshopt-glb.ts';
import { ROOT } from '../../helpers/render.ts';

type Json = Record<string, any>;

const FIXTURES = join(ROOT, 'tests/fixtures/compressed');
const fixture = (name: string) => new Uint8Array(readFileSync(join(FIXTURES, name)));

/** A .gltf of the fixtures, its JSON edited, loaded with its .bin beside it. */
async function loadFixture(
  name: string,
  bin: string,
  edit: (j: Json, bin: Uint8Array) => void = () => {},
  decoders: GltfDecoders = nodeGltfDecoders(),
) {
  const json = JSON.parse(new TextDecoder().decode(fixture(name))) as Json;
  const data = fixture(bin).slice();
  edit(json, data);
  const files = new Map([[bin, data]]);
  for (const im of json.images ?? []) files.set(im.uri, fixture(im.uri));
  const bytes = new TextEncoder().encode(JSON.stringify(json));
  return loadGltf(bytes, name, { ...(await memoryOptions(files)), decoders });
}

async function refused(edit: (j: Json, bin: Uint8Array) => void, pattern: RegExp): Promise<void> {
  const error = await loadFixture('Box.gltf', 'Box.bin', edit).then(
    () => null,
    (e: unknown) => e,
  );
  expect(error).toBeInstanceOf(GltfError);
  expect((error as Error).message).toMatch(pattern);
}

describe('Draco-compressed files', () => {
  it('the sample files decode to the counts of their accessors', async () => {
    for (const [name, bin, triangles] of [
      ['Box.gltf', 'Box.bin', 12],
      ['DracoSparseMesh.gltf', 'DracoSparseMesh.bin', 102],
      ['MorphPrimitivesTest.gltf', 'MorphPrimitivesTest.bin', 32],
      ['CesiumMilkTruck.gltf', 'CesiumMilkTruck_data.bin', 3624],
    ] as const) {
      const m = await loadFixture(name, bin);
      // Meshes drawn by several nodes are instanced (the milk truck's wheels): their
      // triangles count once per instance.
      let instanced = 0;
      for (const k of m.instances?.mesh ?? []) {
        const mesh = m.instances!.meshes[k];
        instanced += mesh.indices.length / 3 + mesh.skipped;
      }
      expect(m.indices.length / 3 + m.skipped + instanced).toBe(triangles);
      expect(m.positions.every(Number.isFinite)).toBe(true);
      expect(m.warnings.filter((w) => w.includes('KHR_draco'))).toEqual([]);
    }
  });

  it('Box: the decoded cube spans ±0.5 (its accessors’ min/max)', async () => {
    const m = await loadFixture('Box.gltf', 'Box.bin');
    expect(Array.from(m.bounds).map((v) => Math.round(v * 1000) / 1000)).toEqual([
      -0.5, -0.5, -0.5, 0.5, 0.5, 0.5,
    ]);
  });

  it("the header's counts, read without decoding (edgebreaker, Draco 2.2)", () => {
    const bin = fixture('Box.bin');
    expect(peekDracoCounts(bin.subarray(0, 118))).toEqual({
      version: '2.2',
      method: 1,
      faces: 12,
      points: null,
    });
    // The sequential method declares its points too (DracoSparseMesh, MorphPrimitivesTest).
    expect(peekDracoCounts(fixture('DracoSparseMesh.bin'))).toEqual({
      version: '2.2',
      method: 0,
      faces: 102,
      points: 62,
    });
    // Metadata (flag 0x8000) is skipped: no attribute metadata, one geometry entry a = b.
    const meta = new Uint8Array(118 + 7);
    meta.set(bin.subarray(0, 9));
    meta.set([0x00, 0x80, 0, 1, 1, 0x61, 1, 0x62, 0], 9);
    meta.set(bin.subarray(11, 118), 18);
    expect(peekDracoCounts(meta)).toMatchObject({ method: 1, faces: 12 });
    expect(peekDracoCounts(Uint8Array.of(1, 2, 3))).toMatch(/no "DRACO" header/);
    expect(peekDracoCounts(bin.subarray(0, 12))).toMatch(/ends early/);
  });

  it('a platform without the decoder refuses the required extension, by name', async () => {
    await expect(loadFixture('Box.gltf', 'Box.bin', undefined, {})).rejects.toThrow(
      /^glTF: extensionsRequired: the file requires "KHR_draco_mesh_compression", which pathwise does not support$/,
    );
  });
});

describe('hostile Draco streams: one GltfError naming the primitive', () => {
  const P = String.raw`^glTF: meshes\[0\]\.primitives\[0\]\.extensions\.KHR_draco_mesh_compression`;
  it('a stream that claims more triangles than the indices accessor: refused before decoding', () =>
    refused(
      (j) => (j.accessors[0].count = 30),
      new RegExp(
        P + ': the Draco stream declares 12 triangles, more than the 10 of its indices accessor$',
      ),
    ));

  it('a sequential stream that claims more points than the POSITION accessor', async () => {
    const error = await loadFixture('DracoSparseMesh.gltf', 'DracoSparseMesh.bin', (j) => {
      for (let a = 1; a <= 6; a++) j.accessors[a].count = 50;
    }).then(
      () => null,
      (e: unknown) => e,
    );
    expect(error).toBeInstanceOf(GltfError);
    expect((error as Error).message).toMatch(
      new RegExp(
        P + ': the Draco stream declares 62 points, more than the 50 of its POSITION accessor$',
      ),
    );
  });

  it('accessors that claim more than the stream decodes to', async () => {
    await refused(
      (j) => (j.accessors[0].count = 42),
      new RegExp(
        P + String.raw`: decodes to 36 indices, but accessors\[0\] \(the indices\) has count 42$`,
      ),
    );
    await refused(
      (j) => {
        j.accessors[1].count = 30;
        j.accessors[2].count = 30;
      },
      new RegExp(
        P +
          String.raw`\.attributes\.NORMAL: the stream decodes to 24 points, but accessors\[1\] has count 30$`,
      ),
    );
  });

  it('an attribute id the stream lacks, and a semantic the primitive lacks', async () => {
    await refused(
      (j) =>
        (j.meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.attributes.NORMAL = 7),
      new RegExp(
        P + String.raw`\.attributes\.NORMAL: the Draco stream has no attribute of unique id 7$`,
      ),
    );
    await refused(
      (j) =>
        (j.meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.attributes.TEXCOORD_0 = 2),
      new RegExp(
        P + String.raw`\.attributes\.TEXCOORD_0: names an attribute the primitive does not have$`,
      ),
    );
  });

  it('a damaged or foreign stream', async () => {
    await refused(
      (_j, bin) => void bin.fill(0x11, 0, 5),
      new RegExp(
        P + String.raw`\.bufferView: bufferViews\[0\] is not a Draco stream \(no "DRACO" header\)$`,
      ),
    );
    await refused(
      (_j, bin) => void bin.fill(0xff, 20, 118),
      new RegExp(P + String.raw`\.bufferView: the Draco stream cannot be decoded \(.+\)$`),
    );
  });
});

describe('decoders are loaded only for files that use them', () => {
  const throwing: GltfDecoders = {
    meshopt() {
      throw new Error('the meshopt getter was called');
    },
    draco() {
      throw new Error('the Draco getter was called');
    },
  };

  it('a plain file calls no getter', async () => {
    const m = await loadGltf(quadGlb(), 'plain.glb', {
      ...(await memoryOptions()),
      decoders: throwing,
    });
    expect(m.indices.length).toBe(6);
  });

  it('a meshopt file calls only the meshopt getter, a Draco file only the Draco one', async () => {
    const node = nodeGltfDecoders();
    await loadGltf(await meshoptQuadGlb(), 'm.glb', {
      ...(await memoryOptions()),
      decoders: { meshopt: node.meshopt, draco: throwing.draco },
    });
    await loadFixture('Box.gltf', 'Box.bin', undefined, {
      meshopt: throwing.meshopt,
      draco: node.draco,
    });
  });

  it('a getter that fails is one GltfError naming the extension', async () => {
    await expect(
      loadGltf(await meshoptQuadGlb(), 'm.glb', { ...(await memoryOptions()), decoders: throwing }),
    ).rejects.toThrow(
      /^glTF: EXT_meshopt_compression: the decoder could not be loaded \(the meshopt getter was called\)$/,
    );
  });
});
