/**
 * Pieces of the light-sampling tests' scenes (tests/unit/core/light-pdf.test.ts,
 * light-bvh.test.ts): two emissive meshes — an icosphere lamp (material `lamp`) and a
 * two-triangle sheet (material `dim`) — and a small striped environment map.
 */
import type { EnvironmentMapDesc } from '../../src/core/scene/format/types.ts';
import { icosphere } from './mesh-gen.ts';

export function lampMeshes(): unknown[] {
  const lamp = icosphere(1, 0.3, [0.5, 1.5, 0.2]);
  return [
    {
      type: 'mesh',
      material: 'lamp',
      positions: Array.from(lamp.positions),
      indices: Array.from(lamp.indices),
    },
    {
      type: 'mesh',
      material: 'dim',
      positions: [-1, 2, -1, 1, 2, -1, 1, 2, 1, 5, 2, 1],
      indices: [0, 1, 2, 0, 2, 3],
    },
  ];
}

/** A 16 × 8 map of stripes, rotated 40°. */
export function stripedMap(): EnvironmentMapDesc {
  const w = 16;
  const h = 8;
  const rgb = new Float32Array(w * h * 3);
  for (let i = 0; i < rgb.length; i++) rgb[i] = ((i * 7) % 11) / 5;
  return {
    type: 'map',
    file: 'test.pfm',
    scale: [1, 1, 1],
    rotationY: 40,
    image: { width: w, height: h, rgb },
  };
}
