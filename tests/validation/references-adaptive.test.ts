/**
 * Adaptive sampling is unbiased (issue 23, deliverable 2): a quarter of the classic
 * reference scenes and the scenes of issue 8, rendered with adaptive sampling
 * (src/core/film/adaptive.ts: a uniform pilot, then per-pixel rates from the
 * neighbours' pilot error), against Mitsuba 3 and the native anchor. The tests and
 * their false-alarm rate (one Bonferroni budget with references.test.ts and the mesh
 * files) are in reference-check.ts.
 */
import { expect, it } from 'vitest';
import { adaptiveNames, referenceSuite } from './reference-check.ts';

it('renders enough scenes adaptively, the scenes of issue 8 among them', () => {
  expect(adaptiveNames.length).toBeGreaterThanOrEqual(12);
  for (const issue of ['issue-sphere-floor', 'issue-grazing-quad']) {
    expect(adaptiveNames).toContain(issue);
  }
});

referenceSuite(adaptiveNames, false, true);
