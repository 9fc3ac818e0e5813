/**
 * A KTX2 texture's header, level index and format, read and checked without
 * transcoding (KTX File Format Specification 2.0, §3 "File structure"; glTF
 * KHR_texture_basisu, "KTX2 File Requirements"). The Basis transcoder trusts the
 * header: a 73 KB file that claims 16384² grew its heap to 1.15 GB before failing,
 * and 200 zero bytes pass its `isValid` (research note decoders.md §4). So every size
 * is read here, each level's bytes are checked against the block count its size
 * implies, and the caller puts the size through the texture budget (TextureLayout)
 * before any transcoder is loaded.
 *
 * Only what KHR_texture_basisu allows is accepted: a 2D texture (no depth, layers or
 * faces), vkFormat 0, and Basis Universal data: ETC1S with BasisLZ (scheme 1) or
 * UASTC, plain (0) or with Zstandard (2). Errors are FormatError('KTX2', …).
 */
import { FormatError } from '../util/format-error.ts';

export const KTX2_IDENTIFIER = [
  0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a,
];

/** Data Format Descriptor colour models (Khronos Data Format Specification 1.3, §5.6). */
const KHR_DF_MODEL_ETC1S = 163;
const KHR_DF_MODEL_UASTC = 166;
/** KTX2 §3.1.6 supercompressionScheme. */
const SCHEME_NONE = 0;
const SCHEME_BASISLZ = 1;
const SCHEME_ZSTD = 2;
/** Bytes of the fixed header (identifier to the SGD length) and of one level index entry. */
const HEADER_BYTES = 80;
const LEVEL_BYTES = 24;
/** The BasisLZ global data: its 20-byte header and one 20-byte image descriptor (KTX2 §3.10.2). */
const SGD_HEADER_BYTES = 20;
const SGD_IMAGE_BYTES = 20;

export interface Ktx2Level {
  width: number;
  height: number;
  byteOffset: number;
  byteLength: number;
}

export interface Ktx2Info {
  width: number;
  height: number;
  /** Level 0 (the largest) first. */
  levels: Ktx2Level[];
  model: 'ETC1S' | 'UASTC';
  supercompression: number;
}

export function isKtx2(b: Uint8Array): boolean {
  return b.length >= 12 && KTX2_IDENTIFIER.every((v, i) => b[i] === v);
}

/** Reads and checks the header of a KTX2 file holding Basis Universal data. */
export function readKtx2Info(b: Uint8Array): Ktx2Info {
  const fail = (m: string): never => {
    throw new FormatError('KTX2', m);
  };
  if (!isKtx2(b)) fail('no KTX 20 identifier');
  if (b.length < HEADER_BYTES)
    fail(`truncated: ${b.length} bytes, the header needs ${HEADER_BYTES}`);
  const view = new DataView(b.buffer, b.byteOffset, b.byteLength);
  const u32 = (at: number): number => view.getUint32(at, true);
  // u64 fields: a value past 2^53 cannot lie inside a file, so it is refused as such.
  const u64 = (at: number, name: string): number => {
    const v = view.getUint32(at + 4, true) * 2 ** 32 + view.getUint32(at, true);
    if (v > b.length)
      fail(`${name} ${v} (byte ${at}) is past the end of the ${b.length}-byte file`);
    return v;
  };
  const vkFormat = u32(12);
  const [width, height, depth, layers, faces] = [u32(20), u32(24), u32(28), u32(32), u32(36)];
  const levelCount = Math.max(1, u32(40));
  const scheme = u32(44);
  if (vkFormat !== 0)
    fail(`vkFormat ${vkFormat} is not Basis Universal (KHR_texture_basisu requires vkFormat 0)`);
  if (width < 1 || height < 1) fail(`size ${width}×${height} is not a 2D image size`);
  if (depth !== 0 || layers !== 0 || faces !== 1)
    fail(
      `a 3D, array or cube texture (depth ${depth}, layers ${layers}, faces ${faces}); glTF takes 2D`,
    );
  // KTX2 §3.1.5: at most a full mip chain.
  const maxLevels = Math.floor(Math.log2(Math.max(width, height))) + 1;
  if (levelCount > maxLevels)
    fail(`${levelCount} levels, more than the ${maxLevels} of a full chain for ${width}×${height}`);
  if (HEADER_BYTES + levelCount * LEVEL_BYTES > b.length)
    fail(`truncated: the index of ${levelCount} levels ends past byte ${b.length}`);

  // The Data Format Descriptor's basic block: its colour model says ETC1S or UASTC.
  const dfdOffset = u32(48);
  const dfdLength = u32(52);
  if (dfdLength < 16 || dfdOffset + dfdLength > b.length)
    fail(`the format descriptor (${dfdLength} bytes at ${dfdOffset}) is missing or past the end`);
  const colorModel = b[dfdOffset + 12];
  let model: Ktx2Info['model'];
  if (colorModel === KHR_DF_MODEL_ETC1S && scheme === SCHEME_BASISLZ) model = 'ETC1S';
  else if (colorModel === KHR_DF_MODEL_UASTC && (scheme === SCHEME_NONE || scheme === SCHEME_ZSTD))
    model = 'UASTC';
  else
    return fail(
      `colour model ${colorModel} with supercompression ${scheme} is not Basis Universal ` +
        `(ETC1S with BasisLZ, or UASTC plain or with Zstandard)`,
    );

  const levels: Ktx2Level[] = [];
  for (let i = 0; i < levelCount; i++) {
    const at = HEADER_BYTES + i * LEVEL_BYTES;
    const w = Math.max(1, width >>> i);
    const h = Math.max(1, height >>> i);
    const byteOffset = u64(at, `level ${i} byteOffset`);
    const byteLength = u64(at + 8, `level ${i} byteLength`);
    const uncompressed = view.getUint32(at + 20, true) * 2 ** 32 + view.getUint32(at + 16, true);
    if (byteOffset + byteLength > b.length)
      fail(
        `level ${i} (${byteLength} bytes at ${byteOffset}) ends past the end of the ${b.length}-byte file`,
      );
    if (byteLength === 0) fail(`level ${i} is empty`);
    if (model === 'UASTC') {
      // UASTC: 16 bytes per 4×4 block, so the level's (uncompressed) length is exact.
      const expected = Math.ceil(w / 4) * Math.ceil(h / 4) * 16;
      const actual = scheme === SCHEME_ZSTD ? uncompressed : byteLength;
      if (actual !== expected || (scheme === SCHEME_NONE && uncompressed !== byteLength))
        fail(
          `level ${i} (${w}×${h}) declares ${actual} bytes of UASTC blocks; ` +
            `${Math.ceil(w / 4)}×${Math.ceil(h / 4)} blocks need ${expected}`,
        );
    }
    levels.push({ width: w, height: h, byteOffset, byteLength });
  }
  if (model === 'ETC1S') checkBasisLz(b, view, levels, fail);
  return { width, height, levels, model, supercompression: scheme };
}

/**
 * BasisLZ's global data (KTX2 §3.10.2): the codebooks' lengths must add up to the
 * SGD's, and each level's image descriptor must place its slices inside that level.
 */
function checkBasisLz(
  b: Uint8Array,
  view: DataView,
  levels: Ktx2Level[],
  fail: (m: string) => never,
): void {
  const u32 = (at: number): number => view.getUint32(at, true);
  const hi = u32(68) + u32(76);
  const sgdOffset = u32(64);
  const sgdLength = u32(72);
  const images = levels.length;
  const fixed = SGD_HEADER_BYTES + images * SGD_IMAGE_BYTES;
  if (hi !== 0 || sgdLength < fixed || sgdOffset + sgdLength > b.length)
    fail(
      `the BasisLZ global data (${sgdLength} bytes at ${sgdOffset}) is missing, short or past the end`,
    );
  const books = u32(sgdOffset + 4) + u32(sgdOffset + 8) + u32(sgdOffset + 12) + u32(sgdOffset + 16);
  if (fixed + books !== sgdLength)
    fail(`the BasisLZ global data is ${sgdLength} bytes, its parts add up to ${fixed + books}`);
  for (let i = 0; i < images; i++) {
    const d = sgdOffset + SGD_HEADER_BYTES + i * SGD_IMAGE_BYTES;
    const [rgbAt, rgbLength, alphaAt, alphaLength] = [
      u32(d + 4),
      u32(d + 8),
      u32(d + 12),
      u32(d + 16),
    ];
    const n = levels[i].byteLength;
    if (rgbLength === 0 || rgbAt + rgbLength > n || alphaAt + alphaLength > n)
      fail(
        `level ${i}'s slices (${rgbLength} + ${alphaLength} bytes) do not lie inside its ${n} bytes`,
      );
  }
}
