/**
 * World space after the node transforms (src/core/gltf/validate-world.ts, cameras.ts):
 * every number of these files is finite, and the products are not; issue 27 found each
 * rendered as an all-zero image (every sample dropped as non-finite, exit 0), as the
 * environment alone, or with a message about something else ("zero-length normal").
 */
import { describe, expect, it } from 'vitest';
import { GltfError } from '../../../src/core/gltf/errors.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import { loadBareModel } from '../../../src/core/scene/load/bare-scene.ts';
import { quadGlb } from '../../fuzz/gltf-samples.ts';
import { memoryOptions } from '../../helpers/gltf.ts';
import { renderSampled } from '../../helpers/render.ts';

type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

async function refused(edit: (json: Json) => void, pattern: RegExp): Promise<void> {
  let error: unknown = null;
  try {
    await loadGltf(quadGlb({ edit }), 'far.glb', await memoryOptions());
  } catch (e) {
    error = e;
  }
  expect(error).toBeInstanceOf(GltfError);
  expect((error as Error).message).toMatch(pattern);
}

describe('world space is checked after the transforms', () => {
  it('a node at 1e308: its triangles round to one point', () =>
    refused((j) => {
      j.nodes[0].translation = [1e308, 0, 0];
    }, /^glTF: nodes\[0\]: all 2 triangles of meshes\[0\]\.primitives\[0\] have zero area in world space: the node places them at 1\.00e\+308, where doubles are 2\.22e\+292 apart$/));

  it('a translation of 1.7e308 under a parent scaled by 10', () =>
    refused((j) => {
      j.nodes[0].translation = [1.7e308, 0, 0];
      j.nodes.push({ scale: [10, 10, 10], children: [0] });
      j.scenes[0].nodes = [1];
    }, /^glTF: nodes\[0\]: its world translation x is Infinity: the transforms of the node and its parents overflow the double range$/));

  it('a matrix of diag(1e308): the area overflows, not the normal', async () => {
    const diag = (j: Json) => {
      delete j.nodes[0].translation;
      j.nodes[0].matrix = [1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1];
    };
    await refused(
      diag,
      /^glTF: nodes\[0\]: triangle 0 of meshes\[0\]\.primitives\[0\] has an area beyond the double range in world space/,
    );
    // Scaled by (1e200, 1, 1e200): the cofactors a·i reach 1e400, and 0 · Infinity made
    // every normal NaN ("zero-length normal"); scaled first, the normals are the file's.
    const model = await loadGltf(
      quadGlb({
        edit: (j: Json) => {
          j.nodes[0].scale = [1e200, 1, 1e200];
        },
      }),
      'big.glb',
      await memoryOptions(),
    );
    expect(Array.from(model.normals!.subarray(0, 3))).toEqual([0, 0, 1]);
  });

  it('a camera node at 1e308 frames a finite image (its target was its position)', async () => {
    for (const z of [1e16, 1e308]) {
      const glb = quadGlb({
        edit: (j: Json) => {
          j.cameras = [{ type: 'perspective', perspective: { yfov: 0.8, znear: 0.1 } }];
          j.nodes.push({ camera: 0, translation: [0.5, 0.5, z] });
          j.scenes[0].nodes.push(1);
        },
      });
      const scene = await loadBareModel(glb, 'far.glb', null, { width: 4, height: 4 });
      expect(scene.camera.position).toEqual([0.5, 0.5, z]);
      expect(scene.camera.target[2]).toBeLessThan(z);
      const image = renderSampled(scene, { spp: 2 });
      expect(image.stats.rejected).toBe(0);
      expect(Array.from(image.mean).every(Number.isFinite)).toBe(true);
      expect(Math.max(...image.mean)).toBeGreaterThan(0);
    }
  });

  it("a camera whose node's matrix is singular is ignored, and the warning says why", async () => {
    for (const matrix of [
      [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 3, 1], // z scaled to 0: no view direction
      [1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 3, 1], // up onto the view direction
    ]) {
      const model = await loadGltf(
        quadGlb({
          edit: (j: Json) => {
            j.cameras = [{ type: 'perspective', perspective: { yfov: 0.8, znear: 0.1 } }];
            j.nodes.push({ camera: 0, matrix });
            j.scenes[0].nodes.push(1);
          },
        }),
        'cam.glb',
        await memoryOptions(),
      );
      expect(model.cameras).toEqual([]);
      expect(model.warnings).toEqual([
        "cameras[0] (at nodes[1]): its node's world matrix is singular, so it has no view direction and up; ignored",
      ]);
    }
  });

  it('a camera on a node scaled by 1e200 is used (its basis is normalised first)', async () => {
    const model = await loadGltf(
      quadGlb({
        edit: (j: Json) => {
          j.cameras = [{ type: 'perspective', perspective: { yfov: 0.8, znear: 0.1 } }];
          j.nodes.push({ camera: 0, translation: [0.5, 0.5, 3], scale: [1e200, 1e200, 1e200] });
          j.scenes[0].nodes.push(1);
        },
      }),
      'cam.glb',
      await memoryOptions(),
    );
    expect(model.cameras.map((c) => [c.position, c.target, c.up])).toEqual([
      [
        [0.5, 0.5, 3],
        [0.5, 0.5, 2],
        [0, 1, 0],
      ],
    ]);
  });
});
