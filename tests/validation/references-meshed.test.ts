/**
 * The classic reference scenes with every quad a two-triangle mesh and a constant
 * environment a 1×1 map (meshedJson in reference-check.ts), against the same
 * Mitsuba 3 and native-anchor references (issue 11 §5). The native anchor renders
 * no meshes or maps, so this is where triangles (emissive ones too) and map
 * sampling meet a double-precision reference: at scales 1e-4 and 1e4, grazing
 * lights, huge receivers, glass boxes around the camera. The tests and their
 * false-alarm rate are in reference-check.ts.
 */
import { describe, expect, it } from 'vitest';
import { meshedNames, referenceSuite } from './reference-check.ts';

describe('the meshed variant', () => {
  it('re-renders at least 40 classic reference scenes', () => {
    expect(meshedNames.length).toBeGreaterThanOrEqual(40);
  });
});

referenceSuite(meshedNames, true);
