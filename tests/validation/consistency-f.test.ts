/** Generated-scene consistency, the many-light family: the light BVH (see consistency-suite.ts, archetypes-many.ts). */
import { MANY_FIRST_SEED, MANY_SCENE_COUNT, consistencySuite } from './consistency-suite.ts';

consistencySuite(MANY_FIRST_SEED, MANY_FIRST_SEED + MANY_SCENE_COUNT - 1, 'many');
