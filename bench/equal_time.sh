#!/usr/bin/env bash
# Issue 25's equal-time comparison: photon, sppm and path at 10, 30 and 120 s on the benchmark
# set, each against two independent long references (their noise floor estimated from their
# spread and subtracted, as `caustica converge` does). Results: bench/results/equal-time/NAME/
# (convergence.csv, images, the HTML report); the CSV rows are printed.
#
# Usage: bash bench/equal_time.sh [SCENE ...]     (default: the set below)
# Environment: REF_SPP (path references, default 4096), TIME (seconds per integrator, 120),
# CHECKPOINTS (10,30,120), THREADS (2), SIZE (e.g. 256x256; default: each scene's own),
# INTEGRATORS (photon,sppm,path; variants as photon:caustic_threshold=1),
# MITSUBA_DATA (a checkout of mitsuba-data: adds Mitsuba's own scenes, which we do not ship:
# its documentation's material preview with rough copper and with glass, and hello.xml).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh >/dev/null
C=./build/caustica
R=bench/results/equal-time
mkdir -p "$R"
ref_spp=${REF_SPP:-4096}
time_budget=${TIME:-120}
checkpoints=${CHECKPOINTS:-10,30,120}
threads=${THREADS:-2}
integrators=${INTEGRATORS:-photon,sppm,path}
size=()
if [ -n "${SIZE:-}" ]; then size=(--width "${SIZE%x*}" --height "${SIZE#*x}"); fi

if [ $# -gt 0 ]; then
  scenes=("$@")
else
  # Made by bench/scenes/make_bench_scenes.py and make_cornell_recessed.py, and our own scenes.
  scenes=(bench/scenes/env-preview.json bench/scenes/glass-env.json bench/scenes/veach-mis.json
          scenes/glossy-cornell.json scenes/cornell-spheres.json scenes/caustic-ring.json
          bench/scenes/cornell-recessed.json scenes/mitsuba/principled.xml scenes/mitsuba/mesh-attributes.xml)
  if [ -n "${MITSUBA_DATA:-}" ]; then
    scenes+=("$MITSUBA_DATA/docs/scenes/bsdf_roughconductor_copper.xml" "$MITSUBA_DATA/docs/scenes/bsdf_dielectric_glass.xml"
             "$MITSUBA_DATA/scenes/hello.xml")
  fi
fi

for scene in "${scenes[@]}"; do
  name=$(basename "${scene%.*}")
  refs=()
  for seed in 1001 1002; do
    ref="$R/$name-ref-$seed.exr"
    if [ ! -f "$ref" ]; then
      if [ "$name" = caustic-ring ]; then
        # Its light is a point: no unbiased method here renders its caustics (light -> mirror ->
        # floor -> eye), so its references are long, dense photon-mapping renders.
        $C render "$scene" --integrator photon --photons 4000000 --caustic-photons 4000000 --spp 64 \
          --seed "$seed" --threads "$threads" "${size[@]}" -o "$ref" -q
      else
        $C render "$scene" --integrator path --spp "$ref_spp" --seed "$seed" --threads "$threads" "${size[@]}" \
          -o "$ref" -q
      fi
    fi
    refs+=(--reference "$ref")
  done
  $C converge "$scene" "${refs[@]}" --integrators "$integrators" --time "$time_budget" \
    --checkpoints "$checkpoints" --threads "$threads" "${size[@]}" --out "$R/$name" -q
  echo "== $name"
  cat "$R/$name/convergence.csv"
done
