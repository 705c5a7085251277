#!/usr/bin/env bash
# Builds Release and runs every benchmark in bench/, printing their tables. bench_surface_cgal
# (CGAL's isotropic_remeshing on bench_surface's inputs) is built, and so run, only where CGAL is
# installed (libcgal-dev, optional); the glob below picks it up then.
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
if [[ ! -x build/bench/bench_surface_cgal ]]; then
    echo "== bench_surface_cgal: not built (CGAL not found; apt-get install libcgal-dev for the CGAL row)"
fi
