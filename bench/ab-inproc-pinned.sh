#!/bin/sh
# A/B of two in-process bundles (bench/inproc.ts built by scripts/build-bench.mjs at two
# commits), sequential and interleaved, every run pinned to one CPU with taskset, two
# independent streams on CPUs far apart. On a shared many-core machine, runs that share a
# core or run side by side swing 2× between rounds; pinned, interleaved pairs do not.
# Prints one JSON line per run (cpu, variant, scene, inproc's result); compare the paired
# ratios of mpaths_per_cpu_s per scene.
#   sh bench/ab-inproc-pinned.sh OLD.mjs NEW.mjs [ROUNDS] [CPU_A] [CPU_B] > runs.jsonl
set -eu
old=$1
new=$2
rounds=${3:-6}
S10K=${TMPDIR:-/tmp}/pathwise-ab-spheres-10k.json
[ -f "$S10K" ] || node bench/scenes.mjs spheres 10000 > "$S10K"
stream() {
  cpu=$1
  r=1
  while [ "$r" -le "$rounds" ]; do
    for s in scenes/cornell.json "$S10K" @million; do
      spp=8
      [ "$s" = "@million" ] && spp=2
      for v in old new; do
        if [ "$v" = old ]; then bundle=$old; else bundle=$new; fi
        echo "{\"cpu\":$cpu,\"v\":\"$v\",\"scene\":\"$s\",\"r\":$(taskset -c "$cpu" node "$bundle" "$s" 128 128 $spp 6 5 2>/dev/null)}"
      done
    done
    r=$((r + 1))
  done
}
out=$(mktemp -d)
stream "${4:-2}" > "$out/a.jsonl" &
stream "${5:-10}" > "$out/b.jsonl" &
wait
cat "$out/a.jsonl" "$out/b.jsonl"
rm -rf "$out"
