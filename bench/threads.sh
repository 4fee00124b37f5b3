#!/usr/bin/env bash
# Two threads against one, end to end (BENCHMARKS.md, "Two threads against one"): path on the
# Cornell bunny, photon on cornell-spheres and its photon pass, each run at 1 and then 2 threads,
# RUNS times alternating, one line per run (take the medians; the machines are shared).
# Usage: RUNS=5 bash bench/threads.sh [caustica executable]   (default ./build/caustica)
set -euo pipefail
cd "$(dirname "$0")/.."
C=${1:-./build/caustica}
field() { grep -E "^$1" | head -n 1 | sed -E 's/.*: ([0-9.]+).*/\1/'; }
for r in $(seq "${RUNS:-5}"); do
  for t in 1 2; do
    a=$("$C" render scenes/cornell-bunny.json --integrator path --spp 32 --threads "$t" -o /tmp/caustica-threads.exr 2>/dev/null | field "render time")
    b=$("$C" render scenes/cornell-spheres.json --spp 8 --threads "$t" -o /tmp/caustica-threads.exr 2>/dev/null | field "render time")
    c=$("$C" render scenes/cornell-spheres.json --spp 1 --photons 1000000 --caustic-photons 1000000 --threads "$t" \
      -o /tmp/caustica-threads.exr 2>/dev/null | field "photon pass time")
    echo "run $r threads $t: path render $a s, photon render $b s, photon pass $c s"
  done
done
