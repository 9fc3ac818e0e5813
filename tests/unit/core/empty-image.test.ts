/**
 * The last guard against a black picture (empty-image.ts): a film that
 * accepted no sample is recognised, and the cause is named from the camera
 * when the camera is what overflows.
 */
import { describe, expect, it } from 'vitest';
import { Film } from '../../../src/core/film/film.ts';
import {
  emptyImageCause,
  emptyImageMessage,
  filmIsEmpty,
} from '../../../src/core/integrator/empty-image.ts';
import type { CameraDesc } from '../../../src/core/scene/format/types.ts';

const CAMERA: CameraDesc = {
  position: [0, 0, 0],
  target: [0, 0, 1],
  up: [0, 1, 0],
  fovY: 40,
  aperture: 0,
  focusDistance: 1,
};

describe('empty image', () => {
  it('a film is empty until one sample is accepted, and stays empty when samples are dropped', () => {
    const film = new Film(4, 3);
    expect(filmIsEmpty(film.sums)).toBe(true);
    expect(film.addSample(1, 1, NaN, 0, 0)).toBe(false);
    expect(film.addSample(2, 1, 2 ** 41, 0, 0)).toBe(false);
    expect(filmIsEmpty(film.sums)).toBe(true);
    // A black sample is a sample: the film is not empty.
    expect(film.addSample(3, 2, 0, 0, 0)).toBe(true);
    expect(filmIsEmpty(film.sums)).toBe(false);
  });

  it('names a camera whose frame overflows', () => {
    const far: CameraDesc = { ...CAMERA, position: [1e308, 0, 0], target: [-1e308, 0, 0] };
    expect(emptyImageCause(far, 16, 16)).toContain('the camera has no finite frame');
    expect(emptyImageMessage(far, 16, 16, 256)).toMatch(
      /^no image: all 256 samples were not finite \(or beyond ±2\^40\) and were left out; the camera has no finite frame/,
    );
  });

  it('names a camera whose rays are not finite', () => {
    // Not a valid scene's camera (the validator refuses it): the guard's own case.
    const broken: CameraDesc = { ...CAMERA, fovY: NaN };
    expect(emptyImageCause(broken, 16, 16)).toMatch(/^the camera's ray through film point/);
  });

  it('otherwise says the radiance was out of range', () => {
    expect(emptyImageCause(CAMERA, 16, 16)).toContain("every path's radiance was out of range");
  });
});
