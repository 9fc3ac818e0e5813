#!/bin/sh
# A/B of the in-process harness (bench/inproc.ts, bundled) against the native anchor, rounds
# interleaved, on the Cornell box, the 10k-sphere field, the bunny and the 1M-triangle mesh,
# one thread each; rates per CPU-second (a shared machine disturbs CPU time least). Prints
# one JSON line per run; bench/ab-summary.mjs takes medians and ratios.
#   sh bench/ab-inproc.sh ROUNDS NAME=BUNDLE.mjs [NAME=BUNDLE.mjs …] > runs.jsonl
# e.g. BUNDLE = dist/bench/inproc.mjs (node scripts/build-bench.mjs) and the same file built
# at an older commit. The anchor: $PATHWISE_NATIVE or /tmp/pathwise-native-anchor/pt.
set -eu
rounds=$1
shift
PT=${PATHWISE_NATIVE:-/tmp/pathwise-native-anchor/pt}
S10K=${TMPDIR:-/tmp}/pathwise-ab-spheres-10k.json
[ -f "$S10K" ] || node bench/scenes.mjs spheres 10000 > "$S10K"
r=1
while [ "$r" -le "$rounds" ]; do
  for spec in "$@"; do
    name=${spec%%=*}
    bundle=${spec#*=}
    for s in scenes/cornell.json "$S10K"; do
      echo "{\"v\":\"$name\",\"scene\":\"$s\",\"r\":$(node "$bundle" "$s" 128 128 8 6 5 2>/dev/null)}"
    done
    for s in @bunny @million; do
      echo "{\"v\":\"$name\",\"scene\":\"$s\",\"r\":$(node "$bundle" "$s" 128 128 4 6 5 2>/dev/null)}"
    done
  done
  if [ -x "$PT" ]; then
    for s in scenes/cornell.json "$S10K"; do
      # Process CPU time of a render long enough that parsing and set-up are negligible.
      cpu=$( { /usr/bin/time -f '%U %S' "$PT" "$s" --width 128 --height 128 --spp 64 --threads 1 \
        --seed 1 --max-bounces 6 --quiet --out /tmp/pathwise-ab-native.pfm > /tmp/pathwise-ab-native.json; } 2>&1 | tail -1)
      echo "{\"v\":\"native\",\"scene\":\"$s\",\"cpu\":\"$cpu\",\"r\":$(cat /tmp/pathwise-ab-native.json)}"
    done
  fi
  r=$((r + 1))
done
