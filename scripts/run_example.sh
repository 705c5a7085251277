#!/usr/bin/env bash
# The main job on the built-in example: installs what is missing, builds Release, adapts the
# paper's initial sphere (data/sphere480.mesh) to the paper's case A size field and prints the
# quality report (input, passes, output; the checker verdict). Output: out/sphere480_A.mesh, its
# report as out/sphere480_A.json; `build/apps/meshstat out/sphere480_A.mesh --svg q.svg` draws it.
# Then a volume from a surface alone: data/spot.obj remeshed at 2 % of its diagonal and filled with
# tets (out/spot.mesh).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHDIMESH_BUILD_TESTS=OFF > /dev/null
echo "building Release (log: build/build.log)..."
cmake --build build -j"$(nproc)" --target adapt meshstat > build/build.log 2>&1 ||
    { tail -40 build/build.log; exit 1; }
mkdir -p out
build/apps/adapt data/sphere480.mesh -o out/sphere480_A.mesh --bench-field A --check \
    --stats out/sphere480_A.json "$@"
build/apps/adapt data/spot.obj -o out/spot.mesh --hsiz 0.05 --check
