#!/usr/bin/env bash
# The main job on the built-in example: installs what is missing, builds Release, adapts the
# paper's initial sphere (data/sphere480.mesh) to the paper's case A size field and prints the
# quality report (input, passes, output; the checker verdict). Output: out/sphere480_A.mesh, its
# report as out/sphere480_A.json; `build/apps/meshstat out/sphere480_A.mesh --svg q.svg` draws it.
# Then a volume from a surface alone: data/spot.obj remeshed at 2 % of its diagonal and filled with
# tets (out/spot.mesh). Last, the Python module's example (examples/adapt_gmsh_mesh.py): a Gmsh
# mesh read with meshio, adapted to a size computed in numpy, written as out/box_with_ball.vtu.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install_deps.sh
# the switches this job needs, set whatever build/ cached (scripts/run_tests.sh shares it; the
# tests' switch is left as it is, only these targets are built)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON -DHDIMESH_BUILD_APPS=ON \
    -DHDIMESH_BUILD_PYTHON=ON > /dev/null
echo "building Release (log: build/build.log)..."
cmake --build build -j"$(nproc)" --target adapt meshstat _hdimesh > build/build.log 2>&1 ||
    { tail -40 build/build.log; exit 1; }
mkdir -p out
build/apps/adapt data/sphere480.mesh -o out/sphere480_A.mesh --bench-field A --check \
    --stats out/sphere480_A.json "$@"
build/apps/adapt data/spot.obj -o out/spot.mesh --hsiz 0.05 --check
PYTHONPATH=build/python /usr/bin/python3 examples/adapt_gmsh_mesh.py data/box_with_ball.msh \
    out/box_with_ball.vtu
