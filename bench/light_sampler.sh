#!/usr/bin/env bash
# The light tree against choosing lights by power: `path` and `photon` at equal time on scenes
# with several lights, each against two independent path references (rendered once, kept in
# bench/results/light-sampler/NAME/), floor-free relMSE as `caustica converge` reports it.
#
# Usage: bash bench/light_sampler.sh NAME SCENE WIDTH HEIGHT REF_SPP SECONDS
# e.g.   bash bench/light_sampler.sh hello $MITSUBA_DATA/scenes/hello.xml 256 192 2048 4
# Environment: THREADS (2).
set -euo pipefail
cd "$(dirname "$0")/.."
name=$1 scene=$2 w=$3 h=$4 ref_spp=$5 seconds=$6
threads=${THREADS:-2}
C=./build/caustica
out=bench/results/light-sampler/$name
mkdir -p "$out"
for seed in 101 102; do
  [ -f "$out/ref-$seed.exr" ] || $C render "$scene" --integrator path --spp "$ref_spp" --width "$w" --height "$h" \
    --seed "$seed" --threads "$threads" -o "$out/ref-$seed.exr" -q 2>/dev/null
done
for sampler in tree power; do
  $C converge "$scene" --width "$w" --height "$h" --threads "$threads" --light-sampler "$sampler" \
    --integrators path,photon --time "$seconds" --checkpoints "$seconds" \
    --reference "$out/ref-101.exr" --reference "$out/ref-102.exr" --out "$out/$sampler" -q 2>/dev/null
  awk -F, -v n="$name" -v s="$sampler" 'NR > 1 {printf "%s %s %s: %s passes, relMSE (floor-free) %s\n", n, s, $1, $3, $6}' \
    "$out/$sampler/convergence.csv"
done
