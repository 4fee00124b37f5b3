#!/usr/bin/env bash
# End-to-end figures for BENCHMARKS.md: long references, equal-time relMSE of photon and path
# at 10, 30 and 60 s (512x512, 2 threads), and scaling (photons, pixels, threads).
# Takes about two hours on 2 cores; results go to bench/results/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh >/dev/null
C=./build/caustica
R=bench/results
mkdir -p "$R"
threads=${THREADS:-2}

# References. cornell-spheres: 8192 spp of path tracing. caustic-ring: its light is a point,
# whose caustics (light -> mirror -> floor -> eye) no unbiased method here can render, so its
# reference is a long, dense photon-mapping render; equal-time errors there measure noise only.
[ -f "$R/ref-cornell-spheres.exr" ] || $C render scenes/cornell-spheres.json --integrator path --spp 8192 \
  --seed 1000 --threads "$threads" -o "$R/ref-cornell-spheres.exr" -q
[ -f "$R/ref-caustic-ring.exr" ] || $C render scenes/caustic-ring.json --integrator photon --photons 4000000 \
  --caustic-photons 4000000 --gather-rays 128 --spp 64 --seed 1000 --threads "$threads" -o "$R/ref-caustic-ring.exr" -q

# Progressive photon (the default), one pair of maps, SPPM and path at equal time.
for scene in cornell-spheres caustic-ring; do
  $C converge "scenes/$scene.json" --reference "$R/ref-$scene.exr" \
    --integrators photon,photon:progressive=false,sppm,path --time 120 \
    --checkpoints 10,20,30,60,120 --threads "$threads" --out "$R/converge-$scene" -q
done

# Scaling: photon pass and kd-tree build against the photon count (n log n expected).
for n in 250000 1000000 4000000; do
  echo "photons $n"
  $C render scenes/cornell-spheres.json --photons "$n" --caustic-photons 0 --spp 1 --width 64 --height 64 \
    --threads "$threads" -o /tmp/caustica-scale.png | grep -E "photon pass time|kd-tree build time|bytes per photon"
done
# Render time against pixel count, and 1 against 2 threads (render and photon pass).
for size in 128 256 512; do
  echo "pixels ${size}x${size}"
  $C render scenes/cornell-spheres.json --spp 2 --width $size --height $size --threads "$threads" \
    -o /tmp/caustica-scale.png | grep -E "^render time"
done
for t in 1 2; do
  echo "threads $t"
  $C render scenes/cornell-spheres.json --photons 1000000 --spp 2 --threads $t -o /tmp/caustica-scale.png |
    grep -E "photon pass time|^render time"
done
