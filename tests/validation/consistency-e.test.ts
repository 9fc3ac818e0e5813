/** Generated-scene consistency, the punctual family: KHR_lights_punctual lights (see consistency-suite.ts, punctual.ts). */
import { PUNCTUAL_FIRST_SEED, PUNCTUAL_SCENE_COUNT, punctualSuite } from './consistency-suite.ts';

punctualSuite(PUNCTUAL_FIRST_SEED, PUNCTUAL_FIRST_SEED + PUNCTUAL_SCENE_COUNT - 1);
