/**
 * The Mitsuba 3 references of the preset scenes (copies of
 * tests/references: 65,536 spp, the scene's own camera and max bounces),
 * fetched only when the error plot needs one. A reference says what the
 * image converges to for exactly that view: the scene's camera, pinhole,
 * and the scene's bounce limit.
 */
import { decodePfm, type CameraDesc, type Scene } from '../core/index.ts';
import { referenceLuminance, type ReferenceLuminance } from './error-grid.ts';
import type { PresetName } from './presets.ts';

const URLS: Record<PresetName, URL> = {
  cornell: new URL('./assets/references/cornell.pfm', import.meta.url),
  spheres: new URL('./assets/references/spheres.pfm', import.meta.url),
  mirror: new URL('./assets/references/mirror.pfm', import.meta.url),
  sky: new URL('./assets/references/metal-sky.pfm', import.meta.url),
};

/** Sizes of the shipped references, known before they are fetched (to size the film). */
export const REFERENCE_SIZES: Record<PresetName, [number, number]> = {
  cornell: [128, 128],
  spheres: [160, 90],
  mirror: [128, 128],
  sky: [128, 128],
};

const loaded = new Map<PresetName, Promise<ReferenceLuminance>>();

export function loadReference(preset: PresetName): Promise<ReferenceLuminance> {
  let pending = loaded.get(preset);
  if (!pending) {
    pending = fetch(URLS[preset])
      .then((r) => {
        if (!r.ok) throw new Error(`${URLS[preset].pathname}: HTTP ${r.status}`);
        return r.arrayBuffer();
      })
      .then((bytes) => {
        const pfm = decodePfm(new Uint8Array(bytes));
        return referenceLuminance(pfm.width, pfm.height, pfm.rgb);
      });
    // A failed fetch may be retried later.
    pending.catch(() => loaded.delete(preset));
    loaded.set(preset, pending);
  }
  return pending;
}

function same(a: readonly number[], b: readonly number[]): boolean {
  return a.length === b.length && a.every((v, i) => v === b[i]);
}

/** Whether the reference of `scene` applies to a render with this camera and bounce limit. */
export function referenceApplies(scene: Scene, camera: CameraDesc, bounces: number): boolean {
  const c = scene.camera;
  return (
    bounces === scene.settings.maxBounces &&
    same(camera.position, c.position) &&
    same(camera.target, c.target) &&
    same(camera.up, c.up) &&
    camera.fovY === c.fovY &&
    camera.aperture === 0
  );
}
