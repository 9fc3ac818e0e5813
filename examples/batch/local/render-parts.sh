#!/bin/sh
# pathwise on one machine with xargs -P: PARTS processes, each rendering one
# range of samples of the same render, then one merge.
#
#   SCENE=scene.json SPP=4096 PARTS=4 OUT=parts FINAL=final.pfm sh render-parts.sh
#
# The same with GNU parallel: replace the xargs line with
#   seq 0 $((PARTS - 1)) | parallel -q -j "$PARTS" sh -c "$RENDER_PART" sh {}
set -eu
: "${SCENE:=scene.json}" "${SPP:=4096}" "${SEED:=1}" "${PARTS:=4}" "${THREADS:=1}" "${OUT:=parts}" "${FINAL:=final.pfm}"
export SCENE SPP SEED PARTS THREADS OUT
mkdir -p "$OUT"
RENDER_PART='I=$1; A=$(( I * SPP / PARTS )); B=$(( (I + 1) * SPP / PARTS ));
pathwise render "$SCENE" --spp "$SPP" --seed "$SEED" --samples "$A:$B" --threads "$THREADS" --out "$OUT/part-$I.film"'
seq 0 $((PARTS - 1)) | xargs -P "$PARTS" -n 1 sh -c "$RENDER_PART" sh
pathwise merge "$OUT"/part-*.film --out "$FINAL" --json
