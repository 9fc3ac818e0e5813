/** Generated-scene consistency, first half (see consistency-suite.ts). */
import { SCENE_COUNT, consistencySuite } from './consistency-suite.ts';

consistencySuite(1, SCENE_COUNT / 2);
