/**
 * The scenes rendered by Mitsuba 3 and the native anchor (references/):
 * the four scenes of issue 8 and 42 generated ones, drawn archetype by
 * archetype so that every light kind and every hard case is present (the
 * generator test checks the coverage of this list).
 */
import type { SceneJson } from './builder.ts';
import { generateScene, type GeneratedScene } from './generate.ts';
import { ISSUE_SCENES } from './issue-scenes.ts';

/** Seeds 2001… of each archetype; how many of each. */
const PER_ARCHETYPE: [string, number][] = [
  ['sphere-over-receiver', 10],
  ['grazing', 6],
  ['glass', 6],
  ['room', 10],
  ['ground', 10],
];

export interface ReferenceScene {
  name: string;
  json: SceneJson;
  generated?: GeneratedScene;
}

export function referenceSet(): ReferenceScene[] {
  const list: ReferenceScene[] = Object.entries(ISSUE_SCENES).map(([name, json]) => ({
    name,
    json,
  }));
  for (const [archetype, count] of PER_ARCHETYPE) {
    for (let seed = 2001; seed < 2001 + count; seed++) {
      const generated = generateScene(seed, { archetype });
      list.push({ name: `gen-${archetype}-${seed}`, json: generated.json, generated });
    }
  }
  return list;
}
