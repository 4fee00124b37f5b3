#!/usr/bin/env bash
# Fuzzes the scene loader with libFuzzer + ASan + UBSan for SECONDS (default 600) in build-fuzz/.
# Usage: scripts/fuzz.sh [SECONDS]. Crashes, hangs and leaks land in build-fuzz/artifacts/.
# CAUSTICA_FUZZ_JOBS=1 limits the build to one job (default: all cores).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
bash scripts/setup.sh clang-14 libfuzzer-14-dev
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DCAUSTICA_FUZZ=ON -DCAUSTICA_TESTS=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz -j"${CAUSTICA_FUZZ_JOBS:-$(nproc)}" --target scene_fuzzer

# Seed corpus: every shipped scene and test scene (the fuzzer adds what it finds to it).
mkdir -p build-fuzz/corpus build-fuzz/artifacts
cp scenes/*.json tests/data/*.json build-fuzz/corpus/
# Regression inputs too, except big ones (they would raise libFuzzer's default -max_len).
if [ -d tests/data/fuzz ]; then find tests/data/fuzz -type f -size -64k -exec cp {} build-fuzz/corpus/ \;; fi

log=build-fuzz/fuzz.log
set +e
build-fuzz/scene_fuzzer build-fuzz/corpus -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
  -dict=fuzz/json.dict -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1 2>&1 | tee "$log" \
  | grep -E --line-buffered "pulse|DONE|ERROR|SUMMARY|artifact|Test unit written"
status=${PIPESTATUS[0]}
set -e
echo "--- final stats (full log: $log)"
grep -E "^#[0-9]+[[:space:]]+DONE|^stat::" "$log" || tail -n 5 "$log"
exit "$status"
