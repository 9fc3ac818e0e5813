/**
 * What tells a glTF model apart before anything is loaded: its file name and the bound
 * on the files it may name. Kept apart from the loader (load.ts, glTF-Transform) so that
 * code which only asks these questions, such as the command line rendering a scene of
 * spheres, does not load the glTF code.
 */

/** Largest external buffer or image file read for a glTF (the scene format's mesh file limit). */
export const GLTF_FILE_BYTES = 1024 * 1024 * 1024;

/** Whether `name` is a glTF model by its extension (`.glb`, `.gltf`). */
export function isModelFileName(name: string): boolean {
  return /\.(glb|gltf)$/i.test(name.split(/[?#]/)[0]);
}
