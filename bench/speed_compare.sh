#!/usr/bin/env bash
# Speed of two builds, in alternating runs on one machine (the ratio is what counts: the
# machines are shared and noisy): `path` camera samples per second on cornell-bunny, and
# `photon` passes per second (photon passes and eye passes together) on cornell-spheres.
#   bash bench/speed_compare.sh OLD_CAUSTICA NEW_CAUSTICA [RUNS]   (default 7 runs each)
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2 runs=${3:-7}
path_args=(render scenes/cornell-bunny.json --integrator path --spp 16 --threads 2 --seed 1 -o /tmp/speed-path.exr)
photon_args=(render scenes/cornell-spheres.json --integrator photon --spp 8 --width 256 --height 256 --threads 2
             --seed 1 -o /tmp/speed-photon.exr)
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
for ((i = 0; i < runs; ++i)); do
  for build in old new; do
    exe=$old; [[ $build == new ]] && exe=$new
    "$exe" "${path_args[@]}" 2>/dev/null | awk -v b=$build '/^samples per second/ {print b, $4}' >> /tmp/speed-path.txt
    "$exe" "${photon_args[@]}" 2>/dev/null |
      awk -v b=$build '/^preprocess time/ {p = $3} /^render time/ {r = $3} /^passes/ {n = $3} END {print b, n / (p + r)}' \
      >> /tmp/speed-photon.txt
  done
done
for what in path photon; do
  o=$(awk '$1 == "old" {print $2}' /tmp/speed-$what.txt | median)
  n=$(awk '$1 == "new" {print $2}' /tmp/speed-$what.txt | median)
  unit="samples/s"; [[ $what == photon ]] && unit="passes/s"
  echo "$what: old $o $unit, new $n $unit, new/old $(awk -v a="$n" -v b="$o" 'BEGIN {printf "%.3f", a / b}') (medians of $runs)"
done
rm -f /tmp/speed-path.txt /tmp/speed-photon.txt
