/**
 * Independent references for the classic family and the scenes of issue 8
 * (issue 8, deliverable 4): pathwise against Mitsuba 3 and the native anchor,
 * and the two references against each other. The tests and their
 * false-alarm rate are in reference-check.ts.
 */
import { describe, expect, it } from 'vitest';
import { FEATURES } from './builder.ts';
import { coverage, manifest, names, referenceSuite } from './reference-check.ts';

export { KNOWN_REFERENCE_ERRORS } from './reference-check.ts';

const classic = names.filter((n) => coverage[n]?.family !== 'mesh');

describe('the reference set', () => {
  it('has at least 40 scenes, rendered by both references, covering every feature of the generator', () => {
    expect(classic.length).toBeGreaterThanOrEqual(40);
    expect(names).toEqual(Object.keys(coverage).sort());
    for (const n of classic) expect(manifest[n].native, n).toBeDefined();
    const features = new Set(classic.flatMap((n) => coverage[n].features ?? []));
    for (const f of FEATURES) expect(features.has(f), f).toBe(true);
    for (const issue of [
      'issue-sphere-floor',
      'issue-ground-sphere-1e3',
      'issue-ground-sphere-1e5',
      'issue-grazing-quad',
    ]) {
      expect(classic).toContain(issue);
    }
  });
});

referenceSuite(classic);
