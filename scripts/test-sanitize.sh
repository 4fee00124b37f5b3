#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer into ./build-sanitize
# and runs the whole test suite under it. This build casts rays through our own BVH
# (CAUSTICA_EMBREE=OFF) and has no MPI (CAUSTICA_MPI=OFF), so that CI builds and tests both ways:
# the README's test command builds with Embree and MPI (and runs the mpirun tests).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh chromium
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCAUSTICA_SANITIZE=ON \
  -DCAUSTICA_EMBREE=OFF -DCAUSTICA_MPI=OFF >/dev/null
cmake --build build-sanitize -j"$(nproc)"
# Full unwinding on malloc: the suppression below must see the library frame.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0
export LSAN_OPTIONS=suppressions="$PWD/.ci/lsan.supp"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd build-sanitize && ctest --output-on-failure -j"$(nproc)" --timeout 1500
