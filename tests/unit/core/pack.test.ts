/**
 * Compile once, share with every worker: a packed scene unpacks into the
 * same scene, bit for bit, whether the buffer is shared or copied, and its
 * arrays are views into that one buffer (nothing is rebuilt).
 */
import { describe, expect, it } from 'vitest';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  packScene,
  unpackScene,
  type CompiledScene,
  type Scene,
} from '../../../src/core/index.ts';
import { SCENE_ARRAYS } from '../../../src/core/scene/compile/compile.ts';
import { randomSpheresScene } from '../../../src/core/scene/load/random-spheres.ts';
import { loadScene } from '../../helpers/render.ts';

function render(scene: Scene, compiled: CompiledScene): Float32Array {
  const tracer = new PathTracer(compiled, {
    width: 24,
    height: 16,
    maxBounces: 4,
    seed: 3,
    camera: scene.camera,
  });
  const film = new Film(24, 16);
  tracer.renderRows(film, 0, 16, 0, 2, new RenderStats());
  return film.sums;
}

describe('packed scenes', () => {
  for (const [name, scene] of [
    ['cornell (no BVH)', loadScene('cornell')],
    ['spheres with a BVH', randomSpheresScene(200, 5)],
  ] as const) {
    it(`${name}: renders bit-identically after a round trip, shared or copied`, () => {
      const compiled = compileScene(scene);
      const reference = render(scene, compiled);
      for (const shared of [true, false]) {
        const packed = packScene(compiled, shared);
        expect(packed.buffer instanceof SharedArrayBuffer).toBe(shared);
        // A structured clone is what a worker receives (a copy for an ArrayBuffer).
        const unpacked = unpackScene(structuredClone(packed));
        expect(unpacked.bvh === null).toBe(compiled.bvh === null);
        for (const a of SCENE_ARRAYS) {
          expect(Array.from(unpacked.data[a])).toEqual(Array.from(compiled.data[a]));
        }
        expect(Array.from(render(scene, unpacked))).toEqual(Array.from(reference));
      }
    });
  }

  it('unpacks into views of the one buffer, not copies', () => {
    const packed = packScene(compileScene(randomSpheresScene(100, 2)), true);
    const a = unpackScene(packed);
    const b = unpackScene(packed);
    expect(a.spheres.buffer).toBe(packed.buffer);
    expect(a.bvh!.nodes.buffer).toBe(packed.buffer);
    // Two workers' scenes share memory: a write through one shows in the other.
    const saved = a.spheres[0];
    a.spheres[0] = 12345;
    expect(b.spheres[0]).toBe(12345);
    a.spheres[0] = saved;
  });

  it('rejects what is not a packed scene', () => {
    const packed = packScene(compileScene(loadScene('cornell')), false);
    expect(() => unpackScene({ ...packed, format: 'x' as 'pathwise-packed/1' })).toThrow(/packed/);
    expect(() => unpackScene({ ...packed, arrays: packed.arrays.slice(1) })).toThrow(/lacks/);
  });
});
