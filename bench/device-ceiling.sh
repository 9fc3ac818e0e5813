#!/bin/sh
# Issue 23's 16-core figures with the machine's own compute ceiling, in one lease:
#   - the ceiling: bench/ceiling.c (a dependent chain of double multiply-adds and square
#     roots, no memory traffic) in 1, 8 and 16 independent processes started together,
#     3 rounds: if 16 run as fast as 1, the cores do not share execution units or clock;
#   - strong scaling of a ~10-second render, bench/device-rounds.sh (as in
#     bench/device-strong.sh): Cornell 512×512, pathwise 256 spp on 16 threads against
#     16 spp on 1, the native anchor 1024 against 64 spp, alternating, 3 rounds;
#   - bench:core (its last table is the whole-process 1-spp render of 10,000 spheres).
# The device takes at most 64 MiB of working tree per call, and the tree (about 47 MiB on
# disk) plus Node (about 20 MiB as `xz --x86 -9e`) is more. So Node travels in two calls
# on the same warm machine: the first copies part .aa of `split -b 10500000 node.xz` to
# /tmp/keep, the second (this script, within the 30 s the machine stays warm) carries the
# other parts in .devrun/ with:
#   .devrun/node.xz.ab, .devrun/node.xz.ac   the rest of Node
#   .devrun/cli.tar.xz    dist/cli without source maps (tar cJf … --exclude='*.map' -C dist cli)
#   .devrun/inc.tar.xz    the anchor's nlohmann headers; .devrun/anchor/ its pt.cpp, build.sh
# Results go to $OUT.
set -u
OUT=${OUT:-out}
mkdir -p "$OUT" /tmp/nd
log() { echo "== $(date -u +%T) $*" >&2; }
cat /tmp/keep/node.xz.aa .devrun/node.xz.ab .devrun/node.xz.ac | xz -d > /tmp/nd/node && chmod +x /tmp/nd/node
export PATH=/tmp/nd:$PATH
mkdir -p dist /tmp/inc && tar xJf .devrun/cli.tar.xz -C dist && tar xJf .devrun/inc.tar.xz -C /tmp/inc
export CPLUS_INCLUDE_PATH=/tmp/inc/inc
(cd .devrun/anchor && OUT_DIR=/tmp/pathwise-native-anchor sh build.sh) >&2
gcc -O2 -o /tmp/ceiling bench/ceiling.c -lm
PT=/tmp/pathwise-native-anchor/pt
node --version >&2; nproc >&2; lscpu > "$OUT/lscpu.txt" 2>&1; cat /proc/loadavg >&2
log "ceiling"
for r in 1 2 3; do
  for n in 1 8 16; do
    t=$( (for k in $(seq $n); do /tmp/ceiling & done; wait) | awk '{print $1}' | sort -n | tr '\n' ' ')
    echo "{\"round\":$r,\"n\":$n,\"seconds\":\"$t\",\"load\":\"$(cut -d' ' -f1 /proc/loadavg)\"}" >> "$OUT/ceiling.jsonl"
    log "ceiling n=$n $t"
  done
done
. bench/device-rounds.sh
strong_rounds
log "bench:core"
node bench/core.mjs --reps 3 --native $PT --out "$OUT/core.json" >&2
log "done"
