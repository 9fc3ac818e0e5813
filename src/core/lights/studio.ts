/**
 * The default environment of a bare model (a `.glb` / `.gltf` rendered without a
 * scene file): a small studio, made here rather than shipped as an image file, so the
 * command line, the widget and the demo light a model identically without fetching
 * anything. An equirectangular map in the scene format's convention
 * (docs/scene-format.md, Environment maps; u = 0.5 looks along +z, toward the framed
 * model's camera), STUDIO_WIDTH × STUDIO_HEIGHT texels, each the radiance at its
 * centre direction:
 * - a soft grey dome, 0.5 at the zenith falling to 0.35 at the horizon, and a darker
 *   floor (0.12) below it, which grounds reflections;
 * - a key softbox (radiance 7) up and to the left of the camera, a large dim fill
 *   (1.2) to the right, and a rim light (3) behind the model, each a disc whose edge
 *   fades over a few degrees (no hard texel edges for the map's sampling to chase).
 * Light sampling takes the map by luminance like any environment map, so the
 * softboxes are found by next-event estimation.
 */
import type { EnvironmentMapDesc } from '../scene/format/types.ts';

/**
 * A bare model's environments: the studio (the default) or none (its own lights only);
 * the command line's `--environment`. Here, not in bare-scene.ts, so the command line's
 * argument parser does not import the glTF loader.
 */
export const BARE_ENVIRONMENTS = ['studio', 'none'] as const;
export type BareEnvironment = (typeof BARE_ENVIRONMENTS)[number];

export const STUDIO_WIDTH = 256;
export const STUDIO_HEIGHT = 128;
/** The `file` a studio environment names (no file is read for it). */
export const STUDIO_FILE = '(studio)';

interface Softbox {
  /** Unit direction toward the light's centre. */
  dir: [number, number, number];
  /** Angular radius and the width of its fading edge, in radians. */
  radius: number;
  edge: number;
  radiance: [number, number, number];
}

function unit(x: number, y: number, z: number): [number, number, number] {
  const l = Math.hypot(x, y, z);
  return [x / l, y / l, z / l];
}

const DEG = Math.PI / 180;

const SOFTBOXES: Softbox[] = [
  { dir: unit(-1, 1.1, 0.9), radius: 14 * DEG, edge: 4 * DEG, radiance: [7, 6.8, 6.4] },
  { dir: unit(1.2, 0.4, 0.7), radius: 30 * DEG, edge: 10 * DEG, radiance: [1.1, 1.15, 1.2] },
  { dir: unit(0.3, 0.8, -1), radius: 12 * DEG, edge: 4 * DEG, radiance: [3, 3, 3] },
];

function smoothstep(a: number, b: number, x: number): number {
  const t = Math.min(1, Math.max(0, (x - a) / (b - a)));
  return t * t * (3 - 2 * t);
}

/** The studio's radiance arriving from unit direction (x, y, z) (the way a ray travels). */
export function studioRadiance(
  x: number,
  y: number,
  z: number,
  out: [number, number, number],
): void {
  // Dome and floor, blended across the horizon over a few degrees.
  const sky = 0.35 + 0.15 * Math.max(0, y);
  const up = smoothstep(-0.03, 0.03, y);
  let r = 0.12 + (sky - 0.12) * up;
  let g = r;
  let b = r * 1.02;
  for (const s of SOFTBOXES) {
    const c = Math.min(1, Math.max(-1, x * s.dir[0] + y * s.dir[1] + z * s.dir[2]));
    const angle = Math.acos(c);
    const w = 1 - smoothstep(s.radius - s.edge, s.radius, angle);
    if (w > 0) {
      r += w * s.radiance[0];
      g += w * s.radiance[1];
      b += w * s.radiance[2];
    }
  }
  out[0] = r;
  out[1] = g;
  out[2] = b;
}

/** The studio as an environment map of the scene format. */
export function studioEnvironment(): EnvironmentMapDesc {
  const width = STUDIO_WIDTH;
  const height = STUDIO_HEIGHT;
  const rgb = new Float32Array(width * height * 3);
  const c: [number, number, number] = [0, 0, 0];
  for (let j = 0; j < height; j++) {
    const theta = ((j + 0.5) / height) * Math.PI;
    const y = Math.cos(theta);
    const s = Math.sin(theta);
    for (let i = 0; i < width; i++) {
      // u = atan2(x, −z) / 2π (scene format, rotationY 0).
      const phi = ((i + 0.5) / width) * 2 * Math.PI;
      studioRadiance(s * Math.sin(phi), y, -s * Math.cos(phi), c);
      rgb.set(c, (j * width + i) * 3);
    }
  }
  return {
    type: 'map',
    file: STUDIO_FILE,
    scale: [1, 1, 1],
    rotationY: 0,
    image: { width, height, rgb },
  };
}
