/**
 * The scene (docs/scene-format.md) around a generated mesh file or environment map: a
 * camera on the model, an emitting quad in view that faces the camera, and a constant
 * environment unless a map is being tested. The quad makes every such case `lit`: a mutated
 * file can remove its own light, never the quad's.
 */
import { ascii } from './bytes.ts';

export const CAMERA = { position: [0, 0.3, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 };

/** Faces −z, toward the camera: cross(u, v) = (0, 0, −0.36). */
const LAMP = {
  type: 'quad',
  corner: [0.8, -1.2, 1],
  u: [0, 0.6, 0],
  v: [0.6, 0, 0],
  material: 'lamp',
};

export function wrapScene(extra: { shapes?: unknown[]; environment?: unknown }): Uint8Array {
  const scene = {
    format: 'pathwise-scene/1',
    camera: CAMERA,
    materials: {
      grey: { type: 'diffuse', albedo: [0.6, 0.6, 0.6] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [4, 4, 4] },
    },
    shapes: [LAMP, ...(extra.shapes ?? [])],
    environment: extra.environment ?? [0.3, 0.35, 0.4],
  };
  return ascii(JSON.stringify(scene, null, 1));
}

/** A scene whose one shape is the mesh file `file`. */
export const meshScene = (file: string): Uint8Array =>
  wrapScene({ shapes: [{ type: 'mesh', file, material: 'grey' }] });

/** A scene lit by the environment map `file` (and the lamp). */
export const envScene = (file: string): Uint8Array =>
  wrapScene({
    shapes: [{ type: 'sphere', center: [0, 0, 0], radius: 0.7, material: 'grey' }],
    environment: { type: 'map', file, scale: 1, rotationY: 30 },
  });
