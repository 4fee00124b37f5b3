#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer into ./build-sanitize
# and runs the test suite under it. This build casts rays through our own BVH
# (CAUSTICA_EMBREE=OFF) and has no MPI (CAUSTICA_MPI=OFF), so that CI builds and tests both ways:
# the README's test command builds with Embree and MPI (and runs the mpirun tests). It also reads
# no OpenVDB files (CAUSTICA_OPENVDB=OFF): OpenVDB is not ours to sanitize, our reader hands it a
# file only in a child process under a memory and time limit, and the README's suite runs the
# .vdb tests and their fuzz cases; the sanitized suite checks the error such a build gives. The
# Python module is left out too (CAUSTICA_PYTHON=OFF): an ASan library cannot be loaded into an
# interpreter that was not started with it, and the module only converts what the suite tests.
# Every tier runs: unit and process as in Release, and the figure tier reduced (this build defines
# CAUSTICA_FIGURES_REDUCED, tests/support/tiers.h): its renders cut down to two samples a pixel
# and 20000 photons, so that the code is exercised, and its figures reported without failing;
# the README's suite holds them to their figures.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh chromium
# -O1, as AddressSanitizer's documentation advises: a third less compile time than -O2.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DCAUSTICA_SANITIZE=ON \
  -DCAUSTICA_EMBREE=OFF -DCAUSTICA_MPI=OFF -DCAUSTICA_OPENVDB=OFF -DCAUSTICA_PYTHON=OFF >/dev/null
cmake --build build-sanitize -j"$(nproc)"
# Fast unwinding on malloc (ASan's default): full unwinding made allocation-heavy tests 10 times
# slower (the Mitsuba reader's 75 s against 7 s); .ci/lsan.supp names the library leak as both see it.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS=suppressions="$PWD/.ci/lsan.supp"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# GCC 12's AddressSanitizer assumes at most 28 bits of mmap randomisation; kernels that use more
# (vm.mmap_rnd_bits 32, as on some CI hosts) make a process fail at random with SIGABRT. The tests
# and every caustica they start run without address randomisation where the container allows it.
norandom=()
if setarch "$(uname -m)" -R true 2>/dev/null; then norandom=(setarch "$(uname -m)" -R); fi
echo "test-sanitize: vm.mmap_rnd_bits $(cat /proc/sys/vm/mmap_rnd_bits 2>/dev/null || echo unknown);" \
  "${norandom[*]:-address randomisation left on}" >&2
cd build-sanitize && "${norandom[@]}" ctest --output-on-failure -j"$(nproc)" --timeout 1500
