/** Generated-scene consistency, second half (see consistency-suite.ts). */
import { SCENE_COUNT, consistencySuite } from './consistency-suite.ts';

consistencySuite(SCENE_COUNT / 2 + 1, SCENE_COUNT);
