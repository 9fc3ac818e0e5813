/**
 * EXT_meshopt_compression and KHR_meshopt_compression (core/gltf/meshopt.ts): files made
 * by meshoptimizer's encoder decode to the exact data (both attribute bitstreams, the
 * KHR COLOR filter), real gltfpack output loads, a fallback buffer without a URI is never
 * read, and each hostile stream gets one GltfError naming the view's extension and the
 * property, before the decoder is asked to allocate anything.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { nodeGltfDecoders } from '../../../src/cli/gltf-node.ts';
import { GltfError } from '../../../src/core/gltf/errors.ts';
import { loadGltf, type GltfDecoders } from '../../../src/core/gltf/load.ts';
import { decodeMeshoptViews, meshoptBudget } from '../../../src/core/gltf/meshopt.ts';
import { memoryOptions } from '../../helpers/gltf.ts';
import {
  meshoptQuadGlb,
  QUAD_COLORS,
  QUAD_INDICES,
  QUAD_POSITIONS,
  type MeshoptQuadOptions,
} from '../../helpers/meshopt-glb.ts';
import { ROOT } from '../../helpers/render.ts';

const FIXTURES = join(ROOT, 'tests/fixtures/compressed');

async function load(bytes: Uint8Array, decoders: GltfDecoders = nodeGltfDecoders()) {
  return loadGltf(bytes, 'model.glb', { ...(await memoryOptions()), decoders });
}

async function refused(options: MeshoptQuadOptions, pattern: RegExp): Promise<void> {
  const bytes = await meshoptQuadGlb(options);
  const error = await load(bytes).then(
    () => null,
    (e: unknown) => e,
  );
  expect(error).toBeInstanceOf(GltfError);
  expect((error as Error).message).toMatch(pattern);
}

describe('meshopt-compressed files', () => {
  for (const [name, version] of [
    ['EXT_meshopt_compression', 0],
    ['KHR_meshopt_compression', 0],
    ['KHR_meshopt_compression', 1],
  ] as const) {
    it(`${name}, attribute bitstream v${version}: decodes to the encoded quad`, async () => {
      let header = -1;
      const bytes = await meshoptQuadGlb({
        name,
        version,
        edit: (_j, bin) => void (header = bin[0]),
      });
      expect(header).toBe(0xa0 + version); // the bitstream the case names
      const m = await load(bytes);
      expect(Array.from(m.positions)).toEqual(Array.from(QUAD_POSITIONS));
      expect(Array.from(m.indices)).toEqual(Array.from(QUAD_INDICES));
      expect(m.warnings).toEqual([]);
    });
  }

  it('the KHR COLOR filter (YCoCg): colours within the 8-bit code of the filter', async () => {
    const m = await load(
      await meshoptQuadGlb({ name: 'KHR_meshopt_compression', version: 1, color: true }),
    );
    expect(m.colors).not.toBeNull();
    // The filter stores Y at 8 bits (error ½ step) and Co, Cg at 8 bits over [−1, 1]
    // (½ of a 2/255 step each); R = Y + Co − Cg adds them, and the decoded value is
    // rounded to unorm8 (½ step): at most 3/255 (observed 1.5/255).
    for (let i = 0; i < 16; i++) {
      expect(Math.abs(m.colors![i] - QUAD_COLORS[i])).toBeLessThanOrEqual(3 / 255 + 1e-6);
    }
  });

  it('the OCTAHEDRAL filter: snorm8 normals decode to +z', async () => {
    const m = await load(await meshoptQuadGlb({ normals: true }));
    expect(m.normals).not.toBeNull();
    expect(Array.from(m.normals!)).toEqual([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1]);
  });

  it('real gltfpack output (pirate.glb, BoxMeshopt.glb) loads, fallback buffer unread', async () => {
    for (const [file, triangles] of [
      ['pirate.glb', 5010],
      ['BoxMeshopt.glb', 12],
    ] as const) {
      const m = await load(new Uint8Array(readFileSync(join(FIXTURES, file))));
      expect(m.indices.length / 3).toBe(triangles);
      expect(m.positions.every(Number.isFinite)).toBe(true);
    }
  });

  it('a fallback buffer with a URI: not read with the decoder, read (and the extension noted) without', async () => {
    const fallback = new Uint8Array(60);
    fallback.set(new Uint8Array(QUAD_POSITIONS.buffer), 0);
    fallback.set(new Uint8Array(QUAD_INDICES.buffer), 48);
    const bytes = await meshoptQuadGlb({
      edit: (j) => {
        j.buffers[1].uri = 'fallback.bin';
        delete j.extensionsRequired;
      },
    });
    // With the decoder the reader is never asked for the file (it has none to give).
    const decoded = await load(bytes);
    expect(Array.from(decoded.positions)).toEqual(Array.from(QUAD_POSITIONS));
    const plain = await loadGltf(bytes, 'model.glb', {
      ...(await memoryOptions(new Map([['fallback.bin', fallback]]))),
      decoders: {},
    });
    expect(Array.from(plain.indices)).toEqual(Array.from(QUAD_INDICES));
    expect(plain.warnings).toEqual([
      'extension "EXT_meshopt_compression" is not supported; its content is ignored',
    ]);
  });

  it('a platform without the decoder: the required extension is refused, by name', async () => {
    const bytes = await meshoptQuadGlb({
      edit: (j) => {
        j.extensionsUsed.push('KHR_draco_mesh_compression');
        j.extensionsRequired.push('KHR_draco_mesh_compression');
      },
    });
    await expect(load(bytes, {})).rejects.toThrow(
      /^glTF: extensionsRequired: the file requires "EXT_meshopt_compression", "KHR_draco_mesh_compression", which pathwise does not support$/,
    );
  });

  it('used but not required, without a decoder: a fallback buffer without data is one error', async () => {
    const bytes = await meshoptQuadGlb({ edit: (j) => delete j.extensionsRequired });
    await expect(load(bytes, {})).rejects.toThrow(/^glTF: buffers\[1\]: has no uri/);
  });
});

describe('hostile meshopt streams: one GltfError naming the place', () => {
  const P = /bufferViews\[0\]\.extensions\.EXT_meshopt_compression/;
  it('a count that lies about the view', () =>
    refused(
      { edit: (j) => (j.bufferViews[0].extensions.EXT_meshopt_compression.count = 5) },
      new RegExp(
        P.source +
          String.raw`\.count: 5 elements of byteStride 12 make 60 bytes, but bufferViews\[0\]\.byteLength is 48$`,
      ),
    ));

  it('a count and byteLength that agree but claim 10⁸ elements from a few bytes', () =>
    refused(
      {
        edit: (j) => {
          j.bufferViews[0].extensions.EXT_meshopt_compression.count = 1e8;
          j.bufferViews[0].byteLength = 12e8;
        },
      },
      new RegExp(
        P.source +
          String.raw`\.count: 100000000 elements of 12 bytes cannot be encoded in \d+ bytes of ATTRIBUTES \(at most 64× the stream\)$`,
      ),
    ));

  it('a stride that lies (the view says 12)', () =>
    refused(
      {
        edit: (j) => {
          const e = j.bufferViews[0].extensions.EXT_meshopt_compression;
          e.byteStride = 16;
          e.count = 3;
        },
      },
      new RegExp(
        P.source + String.raw`\.byteStride: is 16, but bufferViews\[0\]\.byteStride is 12$`,
      ),
    ));

  it('index strides and counts the spec forbids', async () => {
    const Q = String.raw`bufferViews\[1\]\.extensions\.EXT_meshopt_compression`;
    await refused(
      {
        edit: (j) => {
          const e = j.bufferViews[1].extensions.EXT_meshopt_compression;
          e.byteStride = 3;
          e.count = 4;
        },
      },
      new RegExp(Q + String.raw`\.byteStride: must be 2 or 4 for TRIANGLES, got 3$`),
    );
    await refused(
      {
        edit: (j) => {
          const e = j.bufferViews[1].extensions.EXT_meshopt_compression;
          e.count = 4;
          e.byteStride = 2;
          j.bufferViews[1].byteLength = 8;
        },
      },
      new RegExp(Q + String.raw`\.count: must be a multiple of 3 for TRIANGLES, got 4$`),
    );
  });

  it('an unknown mode, and the COLOR filter under the EXT name', async () => {
    await refused(
      { edit: (j) => (j.bufferViews[0].extensions.EXT_meshopt_compression.mode = 'QUADS') },
      new RegExp(
        P.source +
          String.raw`\.mode: must be one of "ATTRIBUTES", "TRIANGLES", "INDICES", got the string "QUADS"$`,
      ),
    );
    await refused(
      { edit: (j) => (j.bufferViews[0].extensions.EXT_meshopt_compression.filter = 'COLOR') },
      new RegExp(
        P.source +
          String.raw`\.filter: must be one of .* for EXT_meshopt_compression, got the string "COLOR"$`,
      ),
    );
  });

  it('a truncated stream: past the buffer, or cut short inside it', async () => {
    await refused(
      { edit: (j) => (j.bufferViews[0].extensions.EXT_meshopt_compression.byteLength += 4096) },
      new RegExp(
        P.source +
          String.raw`: the stream ends at byte \d+, past the end of the \d+ bytes of buffers\[0\]$`,
      ),
    );
    await refused(
      { edit: (j) => (j.bufferViews[0].extensions.EXT_meshopt_compression.byteLength -= 8) },
      new RegExp(
        P.source +
          String.raw`: the compressed stream is malformed \(Malformed buffer data: -?\d+\)$`,
      ),
    );
  });

  it('a stream that is not meshopt data', () =>
    refused(
      { edit: (_j, bin) => void bin.fill(0x55, 0, 4) },
      new RegExp(P.source + ': the stream does not start with a meshopt attribute header'),
    ));

  it('an uncompressed view inside the fallback buffer', () =>
    refused(
      { edit: (j) => delete j.bufferViews[1].extensions },
      /^glTF: bufferViews\[1\]: lies in buffers\[1\], a meshopt fallback buffer that is not read, but is not compressed itself$/,
    ));

  it('the decode budget: all views together, checked before the decoder runs', async () => {
    expect(meshoptBudget(1000, 1 << 30)).toBe(16 * 1024 * 1024);
    expect(meshoptBudget(1e8, 1 << 30)).toBe(1 << 30);
    const json: Record<string, any> = {
      bufferViews: [
        {
          buffer: 0,
          byteLength: 48,
          byteStride: 12,
          extensions: {
            EXT_meshopt_compression: {
              buffer: 0,
              byteLength: 8,
              byteStride: 12,
              count: 4,
              mode: 'ATTRIBUTES',
            },
          },
        },
      ],
      buffers: [{ byteLength: 8 }],
    };
    const decoder = {
      ready: Promise.resolve(),
      decodeGltfBuffer() {
        throw new Error('must not be called');
      },
    };
    const data = [Uint8Array.of(0xa0, 0, 0, 0, 0, 0, 0, 0)];
    await expect(decodeMeshoptViews(json, data, {}, decoder, 40)).rejects.toThrow(
      /^glTF: bufferViews\[0\]\.extensions\.EXT_meshopt_compression\.count: the compressed views decode to more than 40 bytes/,
    );
  });
});
