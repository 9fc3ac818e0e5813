/** Generated-scene consistency, the glTF family: glTF materials and their extensions (see consistency-suite.ts). */
import { GLTF_FIRST_SEED, GLTF_SCENE_COUNT, consistencySuite } from './consistency-suite.ts';

consistencySuite(GLTF_FIRST_SEED, GLTF_FIRST_SEED + GLTF_SCENE_COUNT - 1, 'gltf');
