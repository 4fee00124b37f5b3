#!/usr/bin/env bash
# Set up, build (Release) and run the test suite through CTest: every tier (tests/support/tiers.h).
# Usage: scripts/test.sh [--quick | --tier unit|figure|process]
#   --quick   the unit tier alone (ctest -L unit: about a minute on 2 cores), for the edit-compile-test loop
#   --tier T  one tier: unit, figure (images held to figures) or process (the executable, MPI, browser, notebook)
set -euo pipefail
cd "$(dirname "$0")/.."
tier=""
case "${1:-}" in
  "") ;;
  --quick) tier=unit ;;
  --tier)
    tier="${2:-}"
    [[ "$tier" =~ ^(unit|figure|process)$ ]] || { echo "scripts/test.sh: --tier takes unit, figure or process" >&2; exit 2; } ;;
  *) echo "usage: scripts/test.sh [--quick | --tier unit|figure|process]" >&2; exit 2 ;;
esac
bash scripts/setup.sh chromium  # chromium: the report's browser test opens the HTML page headless
bash scripts/build.sh
cd build
if [ -n "$tier" ]; then
  ctest --output-on-failure -j"$(nproc)" -L "^$tier\$"
else
  ctest --output-on-failure -j"$(nproc)"
fi
