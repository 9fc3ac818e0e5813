/** Generated-scene consistency, the mesh family: meshes and environment maps (see consistency-suite.ts). */
import { MESH_FIRST_SEED, MESH_SCENE_COUNT, consistencySuite } from './consistency-suite.ts';

consistencySuite(MESH_FIRST_SEED, MESH_FIRST_SEED + MESH_SCENE_COUNT - 1, 'mesh');
