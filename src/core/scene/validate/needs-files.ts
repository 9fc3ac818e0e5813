/**
 * Whether a scene names files (meshes, glTF models, environment maps) still to be read:
 * apart from the readers in files.ts, so that a caller can skip loading them (and the
 * glTF code they bring) for a scene that names none.
 */
import type { Scene } from '../format/types.ts';

/** Whether the scene names files that `resolveSceneFiles` must read. */
export function sceneNeedsFiles(scene: Scene): boolean {
  return (
    scene.shapes.some((s) => (s.type === 'mesh' || s.type === 'gltf') && s.data === null) ||
    (scene.environmentMap != null && scene.environmentMap.image === null)
  );
}
