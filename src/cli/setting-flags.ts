/**
 * The command line's name for each setting, in one table: a message about a setting
 * (an override out of range, two film parts that differ) names the flag the user types.
 */
import type { RenderSettings, SettingsDesc } from '../core/index.ts';

export const SETTING_FLAGS = {
  width: '--width',
  height: '--height',
  maxBounces: '--bounces',
  seed: '--seed',
  sampler: '--sampler',
  estimator: '--estimator',
  adaptive: '--adaptive',
  spp: '--spp',
} as const satisfies Record<keyof RenderSettings | 'spp', string>;

/** The flag of a scene setting the command line overrides (validateSettingsOverride's label). */
export function flagOf(key: keyof SettingsDesc): string {
  return SETTING_FLAGS[key];
}
