/**
 * scene.environment (or, without one, a texture scene.background) as pathwise's
 * environment map: the equirectangular texels as a PFM file, linear RGB. three looks an
 * equirectangular map up at u = atan2(d.z, d.x)/2π + 1/2 (equirectUv in
 * common.glsl.js); pathwise at u = atan2(x', −z')/2π with d turned by `rotationY`
 * (docs/scene-format.md): the two agree with rotationY = 90°, plus
 * scene.environmentRotation.y, which three applies the same way (WebGLBackground negates
 * the Euler angles into the lookup's rotation).
 */
import { encodePfm } from '../core/io/pfm.ts';
import { srgbToLinear } from '../core/texture/srgb.ts';
import { readTexels } from './three-pixels.ts';
import type { ThreeObject, ThreeTexture } from './three-shapes.ts';

const EQUIRECT_REFLECTION = 303;
const EQUIRECT_REFRACTION = 304;

export interface SceneEnvironment {
  type: 'map';
  file: string;
  scale: number;
  rotationY: number;
}

export function convertEnvironment(
  scene: ThreeObject,
  files: Map<string, Uint8Array>,
  warn: (m: string) => void,
): SceneEnvironment | null {
  const environment = scene.environment as ThreeTexture | null | undefined;
  const background = scene.background as (ThreeTexture & { isColor?: boolean }) | null | undefined;
  const tex = environment?.isTexture ? environment : background?.isTexture ? background : null;
  if (background && !background.isTexture && background.isColor && !environment?.isTexture) {
    warn(
      'scene.background: a colour lights nothing in three; pathwise shows the (black) environment',
    );
  }
  if (tex === null) return null;
  const where = tex === environment ? 'scene.environment' : 'scene.background';
  if (environment?.isTexture && background?.isTexture && background !== environment) {
    warn('scene.background: differs from scene.environment; pathwise shows the environment');
  }
  if (tex.isCubeTexture || tex.isRenderTargetTexture) {
    warn(
      `${where}: a cube or PMREM texture is not read (give the equirectangular texture); left out`,
    );
    return null;
  }
  if (tex.mapping !== EQUIRECT_REFLECTION && tex.mapping !== EQUIRECT_REFRACTION) {
    warn(`${where}: mapping ${String(tex.mapping)} is read as equirectangular`);
  }
  let texels;
  try {
    texels = readTexels(tex);
  } catch (e) {
    warn(`${where}: ${e instanceof Error ? e.message : String(e)}; left out`);
    return null;
  }
  const n = texels.width * texels.height;
  // encodePfm takes row 0 as the top (+y); the texels' row 0 (v = 0) is three's bottom
  // (−y), so each row is written to its mirrored place.
  const { width, height } = texels;
  const top = new Float32Array(n * 3);
  const srgb = !texels.float && tex.colorSpace === 'srgb';
  for (let i = 0; i < n; i++) {
    const o = ((height - 1 - Math.floor(i / width)) * width + (i % width)) * 3;
    for (let c = 0; c < 3; c++) {
      const v = texels.rgba[i * 4 + c];
      const x = texels.float ? v : srgb ? srgbToLinear(v / 255) : v / 255;
      top[o + c] = Number.isFinite(x) && x > 0 ? x : 0;
    }
  }
  files.set('environment.pfm', encodePfm(texels.width, texels.height, top));
  const rotation = scene.environmentRotation as { x: number; y: number; z: number } | undefined;
  if (rotation && (rotation.x !== 0 || rotation.z !== 0)) {
    warn('scene.environmentRotation: only the rotation about y is kept');
  }
  return {
    type: 'map',
    file: 'environment.pfm',
    scale: typeof scene.environmentIntensity === 'number' ? scene.environmentIntensity : 1,
    rotationY: 90 + ((rotation?.y ?? 0) * 180) / Math.PI,
  };
}
