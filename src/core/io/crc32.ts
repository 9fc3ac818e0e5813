// Moved to src/core/util/crc32.ts so that the image checks (src/core/texture) can use it
// without an import of io, which would close a folder loop (io → geometry →
// scene/format → texture); re-exported here for the existing importers.
export { crc32 } from '../util/crc32.ts';
