#!/usr/bin/env bash
# Renders the figure tests' stored references (tests/data/refs/) again. Each test names its
# references in code (tests/support/reference.h: scene, integrator, settings, spp, size, seed);
# this builds the suite (Release) and runs the figure tests with CAUSTICA_WRITE_REFS set, which
# renders each reference that is missing or whose inputs changed (with --force, every one) in 8
# batches of independent seeds and writes NAME.exr (their mean), NAME.stderr.exr (each pixel's
# standard error) and NAME.json (how it was rendered, by which commit, and the key of its inputs).
# The figure tests then check their own renders against it as before.
# Commit the new files with a message that says why the truth changed.
# Usage: scripts/make-test-refs.sh [--force] [CATCH_TEST_SPEC]   (default spec: [figure])
set -euo pipefail
cd "$(dirname "$0")/.."
mode=1
if [ "${1:-}" = --force ]; then mode=force; shift; fi
spec="${1:-[figure]}"
bash scripts/build.sh
commit=$(git rev-parse --short HEAD)
# The renderer and the scenes it reads; the tests' reference settings are in each reference's key.
git diff --quiet HEAD -- src scenes CMakeLists.txt || commit="$commit with uncommitted changes to src, scenes or the build"
cd build
CAUSTICA_WRITE_REFS=$mode CAUSTICA_REFS_COMMIT="$commit" ./caustica_tests "$spec"
