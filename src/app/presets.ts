/** The canonical scenes, bundled with the page so the first image needs no fetch. */
import cornell from '../../scenes/cornell.json';
import metalSky from '../../scenes/metal-sky.json';
import mirror from '../../scenes/mirror.json';
import spheres from '../../scenes/spheres.json';
import torusUrl from '../../scenes/meshes/torus.obj?url';
import skyUrl from '../../scenes/sky.hdr?url';
import { mappedSceneFiles } from '../view/scene-files.ts';

export const PRESETS = { cornell, spheres, mirror, sky: metalSky } as const;
export type PresetName = keyof typeof PRESETS;

/** The files the presets name, as the bundler serves them. */
export const PRESET_FILES = mappedSceneFiles({
  'meshes/torus.obj': torusUrl,
  'sky.hdr': skyUrl,
});
