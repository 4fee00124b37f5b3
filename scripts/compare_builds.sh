#!/usr/bin/env bash
# Renders every scene in scenes/ (and the Mitsuba Cornell box) with path, photon, sppm and
# whitted at a fixed seed through two builds of caustica and checks that the PFMs are
# bit-identical: the acceptance test of a refactoring that must not change any image.
#   bash scripts/compare_builds.sh OLD_CAUSTICA NEW_CAUSTICA [WORK_DIR]
# Environment: SIZE (default 128: SIZE x SIZE pixels), SPP (default 4), SEED (default 7).
# Exit 0 when every pair is identical, 1 when any differs or fails to render.
set -uo pipefail
cd "$(dirname "$0")/.."
old=$(realpath "$1") new=$(realpath "$2")
work=${3:-$(mktemp -d)}
mkdir -p "$work"
size=${SIZE:-128} spp=${SPP:-4} seed=${SEED:-7}
scenes=(scenes/*.json scenes/mitsuba/cornell-box.xml)
status=0 count=0
for scene in "${scenes[@]}"; do
  name=${scene#scenes/}; name=${name%.*}; name=${name////-}
  for integrator in path photon sppm whitted; do
    args=(render "$scene" --integrator "$integrator" --width "$size" --height "$size" --spp "$spp"
          --seed "$seed" --threads 2 --quiet)
    for build in old new; do
      exe=$old; [[ $build == new ]] && exe=$new
      if ! "$exe" "${args[@]}" -o "$work/$name-$integrator-$build.pfm" >"$work/$name-$integrator-$build.log" 2>&1; then
        echo "FAILED    $name $integrator ($build build; see $work/$name-$integrator-$build.log)"
        status=1
        continue 2
      fi
    done
    count=$((count + 1))
    if cmp -s "$work/$name-$integrator-old.pfm" "$work/$name-$integrator-new.pfm"; then
      echo "identical $name $integrator"
    else
      echo "DIFFERS   $name $integrator"
      status=1
    fi
  done
done
echo "$count pairs compared in $work: $([[ $status == 0 ]] && echo all identical || echo NOT all identical)"
exit $status
