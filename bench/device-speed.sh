#!/bin/sh
# The issue-10 measurements on another machine, in one go (written for the
# 16-core device of bench/results/device/README.md). Run from a copy of the
# tree that holds bin/, dist/cli and dist/bench (npm run build:cli;
# node scripts/build-bench.mjs), bench/, scenes/ and package.json; NODE may
# name the node binary; ANCHOR_SRC a folder with the anchor's pt.cpp and
# build.sh (built here with -march=native). Results go to $OUT.
set -u
OUT=${OUT:-out}
mkdir -p "$OUT"
NODE=${NODE:-node}
log() { echo "== $(date -u +%T) $*" >&2; }
if [ -n "${ANCHOR_SRC:-}" ]; then
  log "building the native anchor"
  (cd "$ANCHOR_SRC" && OUT_DIR=/tmp/pathwise-native-anchor sh build.sh) >&2
fi
"$NODE" --version >&2
nproc >&2

log "bench:core (pathwise against the anchor, same run)"
"$NODE" bench/core.mjs --reps 3 --out "$OUT/core.json" >&2

log "steady state in one thread, no start-up (in-process), against the anchor's render time"
[ -f /tmp/spheres-10k.json ] || "$NODE" bench/scenes.mjs spheres 10000 > /tmp/spheres-10k.json
for s in scenes/cornell.json /tmp/spheres-10k.json; do
  echo "{\"which\":\"pathwise\",\"scene\":\"$s\",\"r\":$("$NODE" dist/bench/inproc.mjs "$s" 128 128 16 6 5)}" >> "$OUT/inproc.jsonl"
  # Before this work (commit 27f0092), when its bundle is there: the same harness.
  if [ -f dist/bench/inproc-base.mjs ]; then
    echo "{\"which\":\"before\",\"scene\":\"$s\",\"r\":$("$NODE" dist/bench/inproc-base.mjs "$s" 128 128 16 6 5)}" >> "$OUT/inproc.jsonl"
  fi
  for k in 1 2 3; do
    echo "{\"which\":\"native\",\"scene\":\"$s\",\"r\":$(/tmp/pathwise-native-anchor/pt "$s" --width 128 --height 128 --spp 16 --threads 1 --max-bounces 6 --quiet --out /tmp/n.pfm)}" >> "$OUT/inproc.jsonl"
  done
done

log "command-line thread scaling, cornell 512x512, 16 spp"
for t in 1 2 4 8 12 16; do
  echo "{\"v8pool\":\"default\",\"r\":$("$NODE" bin/pathwise.js render scenes/cornell.json --width 512 --height 512 --spp 16 --threads $t --json --out /tmp/s.pfm)}" >> "$OUT/cli-scaling.jsonl"
done
log "the same at 16 and 8 threads with V8's platform pool left at Node's 4 (as before)"
for t in 16 8; do
  echo "{\"v8pool\":\"four\",\"r\":$("$NODE" --v8-pool-size=4 bin/pathwise.js render scenes/cornell.json --width 512 --height 512 --spp 16 --threads $t --json --out /tmp/s.pfm)}" >> "$OUT/cli-scaling.jsonl"
done

log "the browser's pool code in Node, shared and transfer modes"
# A browser's V8 sizes its background pool to the machine: so does this run.
"$NODE" --v8-pool-size=0 dist/bench/pool-node.mjs --size 512 --spp 16 --threads 1,4,8,16 --mode shared --out "$OUT/pool-shared.json" > /dev/null
"$NODE" --v8-pool-size=0 dist/bench/pool-node.mjs --size 512 --spp 16 --threads 1,16 --mode transfer --out "$OUT/pool-transfer.json" > /dev/null

log "BVH build, 1M triangle-sized boxes"
"$NODE" dist/bench/bvh-build.mjs 1000000 > "$OUT/bvh-build.jsonl"

log "thread scaling of pathwise and of the native anchor, same run"
"$NODE" bench/scaling.mjs --threads 16 --spp 8 --reps 2 --out "$OUT/scaling.json" >&2

log "independent single-thread processes (the hardware's ceiling)"
"$NODE" bench/processes.mjs --spp 16 --out "$OUT/processes.json" >&2
log "done"
