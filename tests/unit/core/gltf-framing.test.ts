/** The camera of a bare glTF model (src/core/scene/load/framing.ts). */
import { describe, expect, it } from 'vitest';
import { frameModel, FRAMING_FOV_Y } from '../../../src/core/scene/load/framing.ts';

describe('framing a bare model', () => {
  const bounds = Float64Array.of(-1, 0, -1, 1, 2, 1);

  it("uses the file's first camera when it has one", () => {
    const cam = { position: [1, 2, 3], target: [1, 2, 2], up: [0, 1, 0], fovY: 50 } as const;
    const d = frameModel(
      bounds,
      [{ ...cam, position: [1, 2, 3], target: [1, 2, 2], up: [0, 1, 0] }],
      1,
    );
    expect([d.position, d.target, d.fovY]).toEqual([[1, 2, 3], [1, 2, 2], 50]);
  });

  it('otherwise looks at the centre with the whole bounding sphere in view, any aspect', () => {
    for (const aspect of [0.5, 1, 2]) {
      const d = frameModel(bounds, [], aspect);
      expect(d.target).toEqual([0, 1, 0]);
      const [px, py, pz] = d.position;
      const dist = Math.hypot(px, py - 1, pz);
      const r = Math.sqrt(3);
      const half = ((FRAMING_FOV_Y / 2) * Math.PI) / 180;
      const halfX = Math.atan(Math.tan(half) * aspect);
      // The sphere's angular radius fits both half-angles.
      expect(Math.asin(r / dist)).toBeLessThanOrEqual(Math.min(half, halfX) + 1e-12);
      expect(pz).toBeGreaterThan(0);
      expect(py).toBeGreaterThan(1);
    }
  });

  it('an empty model gets a finite camera', () => {
    const d = frameModel(
      Float64Array.of(Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity),
      [],
      1,
    );
    expect([...d.position, ...d.target].every(Number.isFinite)).toBe(true);
  });
});
