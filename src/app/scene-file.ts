/**
 * Opening a scene by the file picker or by dropping it on the page, together with the
 * mesh and environment-map files it names (several files at once: the scene's `.json`
 * and its `.obj`, `.ply`, `.hdr`, `.pfm`, `.glb`, `.gltf`), or a bare glTF model: a
 * `.glb`, or a `.gltf` with its buffers and images. A bad file reports the loader's
 * message; the current scene keeps rendering because the controller only replaces it
 * after validation.
 */
import type { Controller } from '../view/index.ts';
import { droppedSceneFiles } from '../../workers/browser/scene-files.ts';

export function attachSceneFiles(
  getController: () => Controller,
  input: HTMLInputElement,
  dropZone: HTMLElement,
  hint: HTMLElement,
  onLoaded: () => void,
  onError: (message: string) => void,
): void {
  const open = async (files: File[]): Promise<void> => {
    // A scene file, else a model (a scene may name models dropped with it).
    let scenes = files.filter((f) => /\.json$/i.test(f.name));
    if (scenes.length === 0) scenes = files.filter((f) => /\.(glb|gltf)$/i.test(f.name));
    if (scenes.length !== 1) {
      onError(
        scenes.length === 0
          ? 'no scene among the files: open a .json scene with the files it names, ' +
              'or a glTF model (.glb, or .gltf with its buffers and images)'
          : `${scenes.length} scenes or models among the files: open one at a time`,
      );
      return;
    }
    const scene = scenes[0];
    try {
      // The File itself: the loader applies the byte bound and strict UTF-8 to it.
      await getController().setScene(scene, droppedSceneFiles(files));
      onLoaded();
    } catch (e) {
      onError(`${scene.name}: ${e instanceof Error ? e.message : String(e)}`);
    }
  };
  input.addEventListener('change', () => {
    if (input.files && input.files.length > 0) void open(Array.from(input.files));
    input.value = '';
  });
  dropZone.addEventListener('dragover', (e) => {
    e.preventDefault();
    hint.classList.add('visible');
  });
  dropZone.addEventListener('dragleave', () => hint.classList.remove('visible'));
  dropZone.addEventListener('drop', (e) => {
    e.preventDefault();
    hint.classList.remove('visible');
    const files = e.dataTransfer?.files;
    if (files && files.length > 0) void open(Array.from(files));
  });
}
