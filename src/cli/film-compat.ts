/**
 * Whether two films are parts of the same render, and if not, one sentence
 * naming the first difference in the words of the command line (`--seed`,
 * `--bounces`, …), so the user knows which part was rendered wrong.
 */
import type { FilmSettings } from '../core/film/film-file.ts';
import type { FilmIdentity } from './film-file.ts';
import { SETTING_FLAGS } from './setting-flags.ts';

/** The settings compared after the image size, in the order a mismatch is reported. */
const COMPARED = [
  'maxBounces',
  'seed',
  'sampler',
  'estimator',
] as const satisfies readonly (keyof FilmSettings)[];

/**
 * null if `a` and `b` (named `nameA`, `nameB`) can be merged, else why not.
 */
export function explainMismatch(
  nameA: string,
  a: FilmIdentity,
  nameB: string,
  b: FilmIdentity,
): string | null {
  const both = `${nameA} and ${nameB}`;
  if (a.renderer !== b.renderer) {
    return `${both} come from different renderers (${a.renderer} and ${b.renderer}); their samples differ`;
  }
  if (a.scene_sha256 !== b.scene_sha256) {
    return `${both} are renders of different scenes (scene sha256 ${a.scene_sha256.slice(0, 12)}… and ${b.scene_sha256.slice(0, 12)}…)`;
  }
  const sa = a.settings;
  const sb = b.settings;
  if (sa.width !== sb.width || sa.height !== sb.height) {
    return `${both} differ in image size (${sa.width}×${sa.height} and ${sb.width}×${sb.height})`;
  }
  for (const key of COMPARED) {
    if (sa[key] !== sb[key]) {
      return `${both} differ in ${SETTING_FLAGS[key]} (${sa[key]} and ${sb[key]})`;
    }
  }
  if ((sa.adaptive === true) !== (sb.adaptive === true)) {
    const onOff = (s: FilmSettings) => (s.adaptive === true ? 'on' : 'off');
    return `${both} differ in ${SETTING_FLAGS.adaptive} (${onOff(sa)} and ${onOff(sb)})`;
  }
  if (a.key !== b.key) return `${both} have different keys though their settings agree`;
  return null;
}
