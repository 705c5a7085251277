#!/usr/bin/env bash
# Builds Release and runs every benchmark in bench/, printing their tables.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHDIMESH_BUILD_TESTS=OFF > /dev/null
cmake --build build -j"$(nproc)"
for b in build/bench/bench_*; do
    [[ -x "$b" ]] || continue
    echo "== $(basename "$b")"
    "$b" "$@"
done
