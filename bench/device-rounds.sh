# Sourced by bench/device-strong.sh and bench/device-ceiling.sh (from the repository's
# root): the strong scaling of a ~10-second render. Cornell at 512×512, pathwise 256 spp
# on 16 threads against 16 spp on 1 thread (the same paths per second would be 16×), the
# native anchor ($PT) 1024 against 64 spp, alternating, 3 rounds, one JSON line per run
# into $OUT/strong.jsonl. Needs $OUT, $PT and log().
strong_rounds() {
  S=scenes/cornell.json
  log "strong scaling, cornell 512x512"
  for r in 1 2 3; do
    for who in p16 p1 n16 n1; do
      case $who in
        p16) j=$(node bin/pathwise.js render $S --width 512 --height 512 --spp 256 --threads 16 --json --out /tmp/a.pfm) ;;
        p1) j=$(node bin/pathwise.js render $S --width 512 --height 512 --spp 16 --threads 1 --json --out /tmp/a.pfm) ;;
        n16) j=$($PT $S --width 512 --height 512 --spp 1024 --threads 16 --quiet --out /tmp/n.pfm) ;;
        n1) j=$($PT $S --width 512 --height 512 --spp 64 --threads 1 --quiet --out /tmp/n.pfm) ;;
      esac
      echo "{\"round\":$r,\"run\":\"$who\",\"r\":$j}" >> "$OUT/strong.jsonl"
      log "$who $(cat /proc/loadavg)"
    done
  done
}
