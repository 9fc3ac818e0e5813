// Preloaded into the command line under test (node --import): on exit, writes the
// process's peak resident set (getrusage's ru_maxrss, KiB, worker threads included) to
// the file SPECFUZZ_RSS_OUT names, so the harness measures the child and only the child.
import { writeFileSync } from 'node:fs';

const out = process.env.SPECFUZZ_RSS_OUT;
if (out) {
  process.on('exit', () => {
    try {
      writeFileSync(out, String(process.resourceUsage().maxRSS));
    } catch {
      // the harness falls back to its /proc samples
    }
  });
}
