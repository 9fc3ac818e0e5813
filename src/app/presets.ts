/** The canonical scenes, bundled with the page so the first image needs no fetch. */
import cornell from '../../scenes/cornell.json';
import mirror from '../../scenes/mirror.json';
import spheres from '../../scenes/spheres.json';

export const PRESETS = { cornell, spheres, mirror } as const;
export type PresetName = keyof typeof PRESETS;
