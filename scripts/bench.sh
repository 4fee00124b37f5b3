#!/usr/bin/env bash
# Builds and runs the kernel benchmarks (bench/kernels.cpp, bench/embree.cpp) into
# bench/results/kernels.json and prints the table. Installs Google Benchmark, Embree 3 and
# the Stanford bunny (glmark2-data) when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh libbenchmark-dev libembree-dev glmark2-data
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DCAUSTICA_BENCH=ON -DCAUSTICA_TESTS=OFF >/dev/null
cmake --build build-bench -j"$(nproc)" --target caustica_bench
mkdir -p bench/results
./build-bench/caustica_bench --benchmark_out=bench/results/kernels.json --benchmark_out_format=json "$@"
