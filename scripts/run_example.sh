#!/usr/bin/env bash
# The main job on the built-in example: installs what is missing, builds Release, adapts the
# paper's initial sphere (data/sphere480.mesh) to the paper's case A size field and prints the
# quality report. Output: out/sphere480_A.mesh (and .vtu for ParaView).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHDIMESH_BUILD_TESTS=OFF > /dev/null
cmake --build build -j"$(nproc)" --target adapt meshstat
mkdir -p out
build/apps/adapt data/sphere480.mesh -o out/sphere480_A.mesh --bench-field A --check \
    --stats out/sphere480_A.json "$@"
build/apps/meshstat out/sphere480_A.mesh --bench-field A
