/**
 * What the corpus models (tests/corpus/corpus.json) are *currently* expected to say,
 * shared by tests/cli/corpus.test.ts and tests/browser/corpus-widget.test.ts.
 *
 * PENDING lists, per model, every message a render prints today that says something
 * the model uses is ignored or not supported (or the one error that refuses the file).
 * The tests fail when a model prints a message not listed here, and also when a listed
 * message no longer appears: as decoders and extensions land, their entries are
 * removed, until the table is empty and every model renders with nothing ignored.
 * First filled on the branch `corpus` (main at 142dd49, before any issue-25 feature
 * was merged: 25 entries over 11 models); emptied as the decoders, materials, lights,
 * instancing and material variants landed. FILE_NOTES below are notes about faults of the files
 * themselves, which stay.
 */

/** A note that a still image rightly ignores: the rest pose of an animated model. */
export const REST_POSE = /rendered in its rest pose$/;

export const PENDING: Record<string, string[]> = {};

/**
 * Notes about the files themselves, not about pathwise: declared accessor bounds that
 * the decoded vertices exceed (by about 1e-4 of the extent: quantisation and meshopt
 * filters round past the bounds the exporter wrote), and degenerate triangles. They are
 * right to appear and stay.
 */
const bounds = (
  accessor: number,
  vertex: number,
  axis: string,
  v: string,
  lo: string,
  hi: string,
) =>
  `accessors[${accessor}] (POSITION): vertex ${vertex} has ${axis} = ${v}, outside the declared min ${lo} and max ${hi}; the bounds are taken from the vertices`;
export const FILE_NOTES: Record<string, string[]> = {
  bath_day: [
    bounds(15, 51, 'x', '50.856239318847656', '42.44624710083008', '50.8560791015625'),
    bounds(21, 27, 'z', '-19.896827697753906', '-28.145355224609375', '-19.896909713745117'),
    bounds(27, 0, 'x', '11.672492980957031', '6.950694561004639', '11.672379493713379'),
    bounds(36, 2, 'x', '5.821012020111084', '-5.820794582366943', '5.820794582366943'),
    bounds(48, 342, 'y', '52.00392150878906', '-232.1523895263672', '51.99605941772461'),
    bounds(52, 115, 'x', '4.607186317443848', '-4.60688591003418', '4.606884479522705'),
    bounds(56, 9, 'x', '1.8778743743896484', '-1.8777925968170166', '1.8777995109558105'),
    bounds(64, 48, 'x', '4.64912223815918', '-4.470572471618652', '4.648767471313477'),
    bounds(68, 51, 'x', '5.247187614440918', '-5.175860404968262', '5.246726036071777'),
  ],
  minimalistic_modern_bedroom: [
    bounds(2, 4796, 'z', '1.806264877319336', '-1.806157112121582', '1.806156873703003'),
    bounds(6, 1099, 'x', '0.35703590512275696', '-0.3572944104671478', '0.3570345640182495'),
    bounds(10, 14, 'z', '-0.9893454313278198', '-1.0093629360198975', '-0.9893723130226135'),
    'note: skipped 7 triangles of zero area',
  ],
};

/**
 * The pathwise CLI's standard error as messages: without "pathwise: ", without the
 * "note: shapes[i] (FILE): " of a note, and with the model's path of an error replaced
 * by "error:". Rest-pose notes are dropped (they are not ignored extensions).
 */
export function cliMessages(stderr: string, path: string): string[] {
  const out: string[] = [];
  for (const line of stderr.split('\n')) {
    if (!line.startsWith('pathwise: ')) continue;
    let m = line.slice('pathwise: '.length);
    const note = /^note: shapes\[\d+\] \([^)]*\): (.*)$/.exec(m);
    if (note) m = note[1];
    else if (m.startsWith(`${path}: `)) m = `error: ${m.slice(path.length + 2)}`;
    if (!REST_POSE.test(m)) out.push(m);
  }
  return out;
}

/** The widget's warning messages (and error) in the same form. */
export function widgetMessages(warnings: string[], error: string | null): string[] {
  const out = warnings
    .map((m) => m.replace(/^shapes\[\d+\] \([^)]*\): /, ''))
    .filter((m) => !REST_POSE.test(m));
  // The widget's error names the file first ("Box.gltf: glTF: …").
  if (error) out.push(`error: ${error.replace(/^[^:]*: /, '')}`);
  return out;
}

/** Messages not listed, and listed ones that no longer appear. */
export function pendingDiff(name: string, messages: string[]) {
  const expected = [...(PENDING[name] ?? []), ...(FILE_NOTES[name] ?? [])];
  return {
    unexpected: messages.filter((m) => !expected.includes(m)),
    gone: expected.filter((m) => !messages.includes(m)),
  };
}
