#!/bin/sh
# Issue 23's "every core busy" figures on the 16-core device, in one lease:
#   - strong scaling of a ~10-second render: Cornell 512×512, 256 spp on 16
#     threads against 16 spp on 1 thread (the same paths per second would be
#     16×), pathwise and the native anchor alternating, 3 rounds;
#   - the machine's own ceiling for pathwise's code: n independent
#     single-thread processes (bench/processes.mjs);
#   - bench:core, whose last table is the whole-process 1-spp render of
#     10,000 spheres against the anchor.
# Run from a copy of the tree with dist/cli built (npm run build:cli) and
# .devcarry/ holding node.xz (the development machine's node, xz), anchor/
# (the anchor's pt.cpp and build.sh) and inc/nlohmann (its JSON headers).
# Results go to $OUT.
set -u
OUT=${OUT:-out}
mkdir -p "$OUT" /tmp/nd
log() { echo "== $(date -u +%T) $*" >&2; }
xz -d -c .devcarry/node.xz > /tmp/nd/node && chmod +x /tmp/nd/node
export PATH=/tmp/nd:$PATH
export CPLUS_INCLUDE_PATH="$PWD/.devcarry/inc"
(cd .devcarry/anchor && OUT_DIR=/tmp/pathwise-native-anchor sh build.sh) >&2
PT=/tmp/pathwise-native-anchor/pt
node --version >&2
nproc >&2
lscpu > "$OUT/lscpu.txt" 2>&1
cat /proc/loadavg >&2

. bench/device-rounds.sh
strong_rounds

log "independent processes"
node bench/processes.mjs --spp 16 --out "$OUT/processes.json" >&2
log "bench:core"
node bench/core.mjs --reps 3 --native $PT --out "$OUT/core.json" >&2
log "done"
