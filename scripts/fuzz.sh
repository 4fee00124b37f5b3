#!/usr/bin/env bash
# Fuzzes a reader with libFuzzer + ASan + UBSan in build-fuzz/.
# Usage: scripts/fuzz.sh [TARGET] [SECONDS]
#   TARGET: json (the JSON scene loader, default), xml (Mitsuba scenes), mesh (OBJ, PLY, .serialized)
#   SECONDS: default 600. Crashes, hangs and leaks land in build-fuzz/artifacts-TARGET/.
# CAUSTICA_FUZZ_JOBS=1 limits the build to one job (default: all cores).
set -euo pipefail
cd "$(dirname "$0")/.."
target=json
if [[ "${1:-}" =~ ^(json|xml|mesh)$ ]]; then target=$1; shift; fi
seconds="${1:-600}"
bash scripts/setup.sh clang-14 libfuzzer-14-dev
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DCAUSTICA_FUZZ=ON -DCAUSTICA_TESTS=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
case $target in
  json) exe=scene_fuzzer; dict=fuzz/json.dict ;;
  xml) exe=xml_fuzzer; dict=fuzz/xml.dict ;;
  mesh) exe=mesh_fuzzer; dict=fuzz/mesh.dict ;;
esac
cmake --build build-fuzz -j"${CAUSTICA_FUZZ_JOBS:-$(nproc)}" --target "$exe" caustica

# The dictionary: the fixed tokens in fuzz/, and every plugin name and key from the registries
# (`caustica plugins --dict`), so that a new plugin is fuzzed without editing a file.
if [ "$target" != mesh ]; then
  generated=build-fuzz/$target.dict
  { cat "$dict"; echo "# from the registries: caustica plugins --dict $target";
    ASAN_OPTIONS=detect_leaks=0 build-fuzz/caustica plugins --dict "$target"; } > "$generated"
  dict=$generated
fi

# Seed corpus: the shipped and test inputs of that reader (the fuzzer adds what it finds to it).
corpus=build-fuzz/corpus-$target artifacts=build-fuzz/artifacts-$target
mkdir -p "$corpus" "$artifacts"
case $target in
  json)
    # Not the bunny scene: every run of it would read a 70k-triangle mesh.
    find scenes tests/data -maxdepth 1 -name '*.json' ! -name 'cornell-bunny.json' -exec cp {} "$corpus"/ \;
    # Regression inputs too, except big ones (they would raise libFuzzer's default -max_len).
    if [ -d tests/data/fuzz ]; then find tests/data/fuzz -type f -size -64k -exec cp {} "$corpus"/ \;; fi ;;
  xml)
    find scenes tests/data -name '*.xml' -size -64k -exec cp {} "$corpus"/ \; ;;
  mesh)
    # The first byte picks the reader: 0 OBJ, 1 PLY, 2 .serialized.
    python3 fuzz/mesh_seeds.py "$corpus" ;;
esac

log=build-fuzz/fuzz-$target.log
set +e
"build-fuzz/$exe" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -dict="$dict" -artifact_prefix="$artifacts/" -print_final_stats=1 2>&1 | tee "$log" \
  | grep -E --line-buffered "pulse|DONE|ERROR|SUMMARY|artifact|Test unit written"
status=${PIPESTATUS[0]}
set -e
echo "--- final stats (full log: $log)"
grep -E "^#[0-9]+[[:space:]]+DONE|^stat::" "$log" || tail -n 5 "$log"
exit "$status"
