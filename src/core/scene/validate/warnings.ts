/**
 * What a loaded scene's files said that is not an error: glTF extensions and features
 * ignored, primitives skipped, images that could not be used (gltf/load.ts collects
 * them). Each is one line naming the shape; renderers print or emit them.
 */
import type { Scene } from '../format/types.ts';

export function sceneWarnings(scene: Scene): string[] {
  const out: string[] = [];
  scene.shapes.forEach((s, i) => {
    if (s.type !== 'gltf' || s.data === null) return;
    for (const w of s.data.warnings) out.push(`shapes[${i}] (${s.file}): ${w}`);
  });
  return out;
}
