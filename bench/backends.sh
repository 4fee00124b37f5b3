#!/usr/bin/env bash
# Ray-casting backends end to end (BENCHMARKS.md, "Embree"): path samples/s on the Cornell bunny
# and photon-mapping time on cornell-spheres through Embree and through our BVH, and 1 against
# 2 threads, each measured RUNS times alternating (the machines are shared: read the medians).
# Usage: bash bench/backends.sh [caustica executable]   (default ./build/caustica)
set -euo pipefail
cd "$(dirname "$0")/.."
C=${1:-./build/caustica}
RUNS=${RUNS:-3}
field() { grep -E "^$1" | head -n 1 | sed -E 's/.*: ([0-9.]+).*/\1/'; }
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
run() {  # label, then caustica arguments; prints the median of the chosen statistic
  local label=$1 stat=$2; shift 2
  for _ in $(seq "$RUNS"); do "$C" render "$@" -o /tmp/caustica-backends.exr 2>/dev/null | field "$stat"; done | median |
    xargs printf "%-58s %s\n" "$label"
}
for accel in bvh embree; do
  run "path, cornell-bunny, 2 threads, $accel: samples/s" "samples per second" \
    scenes/cornell-bunny.json --integrator path --spp 32 --threads 2 --accel "$accel"
  run "photon, cornell-spheres, 2 threads, $accel: render s" "render time" \
    scenes/cornell-spheres.json --spp 8 --threads 2 --accel "$accel"
  run "photon, cornell-spheres, 2 threads, $accel: photon pass s" "photon pass time" \
    scenes/cornell-spheres.json --spp 1 --photons 1000000 --caustic-photons 1000000 --threads 2 --accel "$accel"
done
for t in 1 2; do
  run "path, cornell-bunny, embree, threads $t: render s" "render time" \
    scenes/cornell-bunny.json --integrator path --spp 32 --threads "$t"
  run "photon, cornell-spheres, embree, threads $t: render s" "render time" \
    scenes/cornell-spheres.json --spp 8 --threads "$t"
  run "photon pass (1M + 1M), cornell-spheres, embree, threads $t: s" "photon pass time" \
    scenes/cornell-spheres.json --spp 1 --photons 1000000 --caustic-photons 1000000 --threads "$t"
done
