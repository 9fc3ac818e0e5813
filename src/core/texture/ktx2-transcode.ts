/**
 * KTX2 / Basis Universal → RGBA8, through a Basis Universal transcoder module
 * (Binomial's, built to WebAssembly; the copy in vendor/basis/) and a KTX2
 * container parser (ktx-parse's `read`), both handed in by the platform: the core
 * imports neither package. Every size was checked by ktx2-header.ts and the texture
 * budget before this runs; it checks them again against what the parser and the
 * transcoder say, and computes the output size in JavaScript (the transcoder's own
 * size wraps at 2^32).
 */
import type { DecodedImage } from './decoded-image.ts';
import { readKtx2Info } from './ktx2-header.ts';

/** The transcoder's KTX2File (basis_universal webgl/transcoder/basis_wrappers.cpp), as used. */
export interface BasisKtx2File {
  isValid(): boolean | number;
  getWidth(): number;
  getHeight(): number;
  getLevels(): number;
  startTranscoding(): boolean | number;
  getImageTranscodedSizeInBytes(level: number, layer: number, face: number, format: number): number;
  transcodeImage(
    dst: Uint8Array,
    level: number,
    layer: number,
    face: number,
    format: number,
    getAlphaForOpaqueFormats: number,
    channel0: number,
    channel1: number,
  ): boolean | number;
  close(): void;
  delete(): void;
}

/** The initialised transcoder module (after `initializeBasis()`), as used. */
export interface BasisModule {
  KTX2File: new (bytes: Uint8Array) => BasisKtx2File;
  transcoder_texture_format: { cTFRGBA32: { value: number } };
}

/** ktx-parse's `read`, as far as it is used. */
export type Ktx2ContainerReader = (bytes: Uint8Array) => {
  pixelWidth: number;
  pixelHeight: number;
  supercompressionScheme: number;
  levels: unknown[];
};

/** Transcodes mip level `level` of a KTX2 file to RGBA8 (top row first, as KHR_texture_basisu requires). */
export type Ktx2Transcoder = (bytes: Uint8Array, level: number) => Promise<DecodedImage>;

/** A transcoder over `basis` and `readContainer`; errors read "cannot decode KTX2: …". */
export function basisKtx2Transcoder(
  basis: BasisModule,
  readContainer: Ktx2ContainerReader,
): Ktx2Transcoder {
  const fail = (m: string): never => {
    throw new Error(`cannot decode KTX2: ${m}`);
  };
  return async (bytes, level) => {
    const info = readKtx2Info(bytes);
    const { width, height } = info.levels[level] ?? fail(`no level ${level}`);
    let container;
    try {
      container = readContainer(bytes);
    } catch (e) {
      return fail(`the container does not parse (${e instanceof Error ? e.message : String(e)})`);
    }
    if (
      container.pixelWidth !== info.width ||
      container.pixelHeight !== info.height ||
      container.levels.length !== info.levels.length ||
      container.supercompressionScheme !== info.supercompression
    )
      fail('the container parser and the header disagree');
    const file = new basis.KTX2File(bytes);
    try {
      if (!file.isValid()) fail('the transcoder refuses the file');
      if (
        file.getWidth() !== info.width ||
        file.getHeight() !== info.height ||
        file.getLevels() !== info.levels.length
      )
        fail('the transcoder reads another size than the header says');
      if (!file.startTranscoding()) fail('the transcoder cannot start (damaged global data?)');
      const format = basis.transcoder_texture_format.cTFRGBA32.value;
      const size = width * height * 4;
      if (file.getImageTranscodedSizeInBytes(level, 0, 0, format) !== size)
        fail(`the transcoder's size for level ${level} is not ${width}×${height}×4`);
      const data = new Uint8Array(size);
      if (!file.transcodeImage(data, level, 0, 0, format, 0, -1, -1))
        fail(`level ${level} does not transcode (damaged ${info.model} data)`);
      return { width, height, data, channels: 4, depth: 8 };
    } finally {
      file.close();
      file.delete();
    }
  };
}
