/** Every format the command line reads, one generator each. */
import { filmGenerator } from './film-gen.ts';
import { gltfGenerator } from './gltf-gen.ts';
import { hdrGenerator } from './hdr-gen.ts';
import { jpegGenerator } from './jpeg-gen.ts';
import { objGenerator } from './obj-gen.ts';
import { pfmGenerator } from './pfm-gen.ts';
import { plyGenerator } from './ply-gen.ts';
import { pngGenerator } from './png-gen.ts';
import { sceneGenerator } from './scene-gen.ts';
import type { Generator } from './types.ts';

export const GENERATORS: readonly Generator[] = [
  plyGenerator,
  objGenerator,
  hdrGenerator,
  pfmGenerator,
  pngGenerator,
  jpegGenerator,
  gltfGenerator,
  filmGenerator,
  sceneGenerator,
];
