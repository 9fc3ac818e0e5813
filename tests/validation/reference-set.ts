/**
 * The scenes rendered by Mitsuba 3 and the native anchor (references/):
 * the four scenes of issue 8 and 42 generated ones, drawn archetype by
 * archetype so that every light kind and every hard case is present (the
 * reference test checks the coverage of this list); and scenes of the mesh
 * family (meshes and environment maps, issue 11 §5), which only Mitsuba
 * renders: the native anchor has neither.
 */
import type { SceneJson } from './builder.ts';
import { generateScene, type GeneratedScene } from './generate.ts';
import { ISSUE_SCENES } from './issue-scenes.ts';

/** Classic family: seeds 2001… of each archetype; how many of each. */
const PER_ARCHETYPE: [string, number][] = [
  ['sphere-over-receiver', 10],
  ['grazing', 6],
  ['glass', 6],
  ['room', 10],
  ['ground', 10],
];

/** Mesh family: seeds 4001… of each archetype; how many of each. */
const MESH_PER_ARCHETYPE: [string, number][] = [
  ['mesh-light', 4],
  ['mesh-room', 5],
  ['mesh-ground', 4],
  ['map-objects', 4],
  ['mesh-glass', 2],
];

export interface ReferenceScene {
  name: string;
  json: SceneJson;
  generated?: GeneratedScene;
  /** Files the scene names (mesh family). */
  files?: Record<string, Uint8Array>;
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
  for (const [archetype, count] of MESH_PER_ARCHETYPE) {
    for (let seed = 4001; seed < 4001 + count; seed++) {
      const name = `gen-${archetype}-${seed}`;
      const generated = generateScene(seed, { archetype, family: 'mesh', filePrefix: name });
      list.push({ name, json: generated.json, generated, files: generated.files });
    }
  }
  return list;
}
