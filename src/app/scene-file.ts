/**
 * Opening a scene file by the file picker or by dropping it on the page.
 * A bad file reports the loader's message; the current scene keeps
 * rendering because the controller only replaces it after validation.
 */
import type { Controller } from '../view/index.ts';

export function attachSceneFiles(
  getController: () => Controller,
  input: HTMLInputElement,
  dropZone: HTMLElement,
  hint: HTMLElement,
  onLoaded: () => void,
  onError: (message: string) => void,
): void {
  const open = async (file: File): Promise<void> => {
    try {
      // The File itself: the loader applies the byte bound and strict UTF-8 to it.
      await getController().setScene(file);
      onLoaded();
    } catch (e) {
      onError(`${file.name}: ${e instanceof Error ? e.message : String(e)}`);
    }
  };
  input.addEventListener('change', () => {
    const file = input.files?.[0];
    if (file) void open(file);
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
    const file = e.dataTransfer?.files[0];
    if (file) void open(file);
  });
}
