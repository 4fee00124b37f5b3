#!/usr/bin/env bash
# Set up, build (Release) and run the whole test suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh chromium  # chromium: the report's browser test opens the HTML page headless
bash scripts/build.sh
cd build && ctest --output-on-failure -j"$(nproc)"
