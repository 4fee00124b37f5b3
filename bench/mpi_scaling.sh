#!/usr/bin/env bash
# MPI scaling for BENCHMARKS.md and docs/cluster.md: the same passes of cornell-spheres.json
# (photon, progressive, 512x512) as 1 process x 1 thread, 1 process x 2 threads, 1 rank x 2
# threads under mpirun, and 2 ranks x 1 thread; each run's wall time, render time and image
# gathering, and whether the images are bit-identical. Needs a build with MPI (scripts/build.sh).
# ROUNDS=3 repeats the whole set, interleaved, so that a noisy moment hits all configurations.
set -euo pipefail
cd "$(dirname "$0")/.."
C=./build/caustica
S=scenes/cornell-spheres.json
spp=${SPP:-8}
out=$(mktemp -d)
mpi="mpirun --allow-run-as-root --oversubscribe"
run() {  # label, command...
  local label=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  "$@" "$S" --spp "$spp" --seed 7 -o "$out/$label.pfm" > "$out/$label.txt" 2>/dev/null
  t1=$(date +%s.%N)
  printf '%-26s wall %6.2f s  render %6.2f s  preprocess %5.2f s  gather %s\n' "$label" \
    "$(echo "$t1 - $t0" | bc)" "$(sed -n 's/^render time: \([0-9.]*\) s/\1/p' "$out/$label.txt")" \
    "$(sed -n 's/^preprocess time: \([0-9.]*\) s/\1/p' "$out/$label.txt")" \
    "$(sed -n 's/^image gathering (in the render time): \([0-9.]*\) s/\1 s/p' "$out/$label.txt")"
}
for round in $(seq "${ROUNDS:-1}"); do
  echo "round $round, $spp passes"
  run 1x1 $C render --threads 1
  run 1x2 $C render --threads 2
  run mpirun-1x2 $mpi -np 1 --bind-to none $C render --threads 2
  run mpirun-2x1 $mpi -np 2 $C render --threads 1
done
for label in 1x2 mpirun-1x2 mpirun-2x1; do
  cmp -s "$out/1x1.pfm" "$out/$label.pfm" && echo "$label: image identical to 1x1" || echo "$label: image DIFFERS from 1x1"
done
rm -rf "$out"
