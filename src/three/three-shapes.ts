/**
 * The parts of three.js objects that the conversion reads, as structural types. The
 * converter never imports three at run time: it recognises objects by three's own
 * `isMesh`/`isMeshPhysicalMaterial`-style flags, so it works with any three release that
 * keeps them (r155 on: physically based light units, `colorSpace`, `uv1`), costs the
 * widget nothing when unused, and cannot load a second copy of three beside the app's.
 */

export interface Vec2 {
  x: number;
  y: number;
}
export interface Vec3 extends Vec2 {
  z: number;
}
export interface Color3 {
  r: number;
  g: number;
  b: number;
}
export interface Mat4 {
  /** Column-major, as three stores it. */
  elements: ArrayLike<number>;
}

export interface ThreeAttribute {
  count: number;
  itemSize: number;
  normalized?: boolean;
  isInterleavedBufferAttribute?: boolean;
  getX(i: number): number;
  getY(i: number): number;
  getZ(i: number): number;
  getW(i: number): number;
}

export interface ThreeGeometry {
  uuid: string;
  isBufferGeometry?: boolean;
  attributes: Record<string, ThreeAttribute | undefined>;
  index: ThreeAttribute | null;
  groups: { start: number; count: number; materialIndex?: number }[];
  morphAttributes?: Record<string, unknown[] | undefined>;
  drawRange?: { start: number; count: number };
}

export interface ThreeImage {
  width?: number;
  height?: number;
  data?: ArrayLike<number> & { BYTES_PER_ELEMENT?: number };
}

export interface ThreeTexture {
  uuid: string;
  name?: string;
  isTexture?: boolean;
  isCubeTexture?: boolean;
  isDataTexture?: boolean;
  isCompressedTexture?: boolean;
  isRenderTargetTexture?: boolean;
  image: unknown;
  /** 'srgb', 'srgb-linear' or '' (NoColorSpace). */
  colorSpace?: string;
  flipY: boolean;
  channel?: number;
  offset: Vec2;
  repeat: Vec2;
  center: Vec2;
  rotation: number;
  wrapS: number;
  wrapT: number;
  magFilter: number;
  minFilter: number;
  mapping?: number;
  /** FloatType 1015, HalfFloatType 1016, UnsignedByteType 1009. */
  type?: number;
  /** RGBAFormat 1023, RGBFormat gone (r137), RedFormat 1028. */
  format?: number;
}

/** Every property the conversion reads from a material, all optional. */
export interface ThreeMaterial {
  uuid: string;
  name?: string;
  type?: string;
  visible?: boolean;
  isMeshStandardMaterial?: boolean;
  isMeshPhysicalMaterial?: boolean;
  isMeshBasicMaterial?: boolean;
  isMeshLambertMaterial?: boolean;
  isMeshPhongMaterial?: boolean;
  [key: string]: unknown;
}

export interface ThreeObject {
  uuid: string;
  name?: string;
  type?: string;
  visible: boolean;
  children: ThreeObject[];
  matrixWorld: Mat4;
  updateWorldMatrix(updateParents: boolean, updateChildren: boolean): void;
  isMesh?: boolean;
  isInstancedMesh?: boolean;
  isSkinnedMesh?: boolean;
  isPoints?: boolean;
  isLine?: boolean;
  isSprite?: boolean;
  isLight?: boolean;
  isScene?: boolean;
  geometry?: ThreeGeometry;
  material?: ThreeMaterial | ThreeMaterial[];
  morphTargetInfluences?: number[];
  count?: number;
  instanceMatrix?: { array: ArrayLike<number> };
  instanceColor?: unknown;
  [key: string]: unknown;
}

export interface ThreeCamera {
  isCamera?: boolean;
  isPerspectiveCamera?: boolean;
  isOrthographicCamera?: boolean;
  matrixWorld: Mat4;
  updateWorldMatrix(updateParents: boolean, updateChildren: boolean): void;
  fov: number;
  zoom: number;
  aspect: number;
  view?: { enabled: boolean } | null;
  filmOffset?: number;
  /** three-gpu-pathtracer's PhysicalCamera. */
  fStop?: number;
  focusDistance?: number;
  bokehSize?: number;
  getFocalLength?(): number;
}

/** A property of `o` that is a three.js texture, or null. */
export function textureOf(o: Record<string, unknown>, key: string): ThreeTexture | null {
  const t = o[key] as ThreeTexture | null | undefined;
  return t && t.isTexture ? t : null;
}

export function colorOf(o: Record<string, unknown>, key: string): [number, number, number] | null {
  const c = o[key] as Color3 | null | undefined;
  return c && typeof c.r === 'number' ? [c.r, c.g, c.b] : null;
}

export function numberOf(o: Record<string, unknown>, key: string, fallback: number): number {
  const v = o[key];
  return typeof v === 'number' ? v : fallback;
}
