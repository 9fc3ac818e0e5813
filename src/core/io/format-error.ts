// Moved to src/core/util/format-error.ts so that the image checks (src/core/texture) can
// throw it without an import of io, which would close a folder loop (io → geometry →
// scene/format → texture); re-exported here for the existing importers.
export { FormatError } from '../util/format-error.ts';
