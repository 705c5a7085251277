#!/usr/bin/env bash
# Checks that the working tree's outputs are bitwise identical to those of commit BASE: builds
# both in Release (BASE from `git archive`, kept in build-bitwise/ for the next call), then
# compares bench_surface --save's surfaces (cmp), bench_adapt's mesh digests, surfremesh's
# adaptive outputs on data/*.obj, scripts/run_example.sh's meshes (sphere480 case A; spot's volume
# from its surface, also with --keep-surface; the Python example's .vtu), a coupled .msh input
# (fandisk at 4 % of its diagonal) written as .msh and .vtu, and meshconvert's writers.
# Every adapt and bench_adapt run is given --threads 1 when its build knows the flag.
#   scripts/bitwise.sh BASE [--cases AC]
# HDIMESH_BITWISE_BASE_ONLY=1 makes BASE's outputs only (they are reused by later calls).
# Prints BITWISE OK and exits 0 when every output matches; names each one that differs otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ $# -ge 1 ]] || { echo "usage: scripts/bitwise.sh BASE [--cases AC]" >&2; exit 2; }
base=$(git rev-parse --verify "$1^{commit}")
shift
cases=AC
[[ "${1:-}" == "--cases" && -n "${2:-}" ]] && cases=$2
jobs=$(nproc)
# HDIMESH_BITWISE_DIR: where BASE's sources, build and outputs are kept (shared by worktrees)
top=${HDIMESH_BITWISE_DIR:-$PWD/build-bitwise}
here=$PWD/build-bitwise
mkdir -p "$top" "$here"

build() { # build SRC DIR
    cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release -DHDIMESH_BUILD_TESTS=OFF > /dev/null
    cmake --build "$2" -j"$jobs" --target adapt surfremesh meshconvert bench_surface bench_adapt _hdimesh \
        > "$2/build.log" 2>&1 || { tail -30 "$2/build.log"; exit 1; }
}

outputs() { # outputs BUILD OUTDIR
    local b=$1 out=$2
    # --threads 1, explicitly, to the builds whose adapt knows it (an older BASE's refuses it);
    # the help is read first, not piped: with pipefail, grep -q's early exit would fail adapt
    local help threads=()
    help=$("$b/apps/adapt" --help 2>&1 || true)
    [[ "$help" == *--threads* ]] && threads=(--threads 1)
    rm -rf "$out" && mkdir -p "$out/uniform" "$out/adaptive"
    "$b/bench/bench_surface" --uniform-only --save "$out/uniform" > "$out/bench_surface.txt"
    "$b/bench/bench_adapt" --cases "$cases" "${threads[@]}" | sed -n '/^mesh digests/,$p' \
        > "$out/digests.txt"
    for m in data/*.obj; do
        "$b/apps/surfremesh" "$m" -o "$out/adaptive/$(basename "$m")" -v 0 > /dev/null
    done
    "$b/apps/adapt" data/sphere480.mesh -o "$out/sphere480_A.mesh" --bench-field A -v 0 \
        "${threads[@]}" > /dev/null
    "$b/apps/adapt" data/spot.obj -o "$out/spot.mesh" --hsiz 0.05 -v 0 "${threads[@]}" > /dev/null
    "$b/apps/adapt" data/spot.obj -o "$out/spot_kept.mesh" --hsiz 0.05 --keep-surface -v 0 \
        "${threads[@]}" > /dev/null
    "$b/apps/adapt" data/fandisk.msh -o "$out/fandisk_4.msh" --hsiz 0.3046 -v 0 "${threads[@]}" \
        > /dev/null
    "$b/apps/adapt" data/fandisk.msh -o "$out/fandisk_4.vtu" --hsiz 0.3046 -v 0 "${threads[@]}" \
        > /dev/null
    for f in msh vtu meshb; do
        "$b/apps/meshconvert" "$out/sphere480_A.mesh" "$out/sphere480_A.$f" > /dev/null
    done
    PYTHONPATH=$b/python /usr/bin/python3 examples/adapt_gmsh_mesh.py data/box_with_ball.msh \
        "$out/box_with_ball.vtu" > /dev/null
}

src_base=$top/src-$base
if [[ ! -d "$src_base" ]]; then
    mkdir -p "$src_base.tmp"
    git archive "$base" | tar -x -C "$src_base.tmp"
    mv "$src_base.tmp" "$src_base"
fi
# BASE's outputs do not change: made once per base and cases, then reused
out_base=$top/out-$base-$cases
if [[ ! -f "$out_base/done" ]]; then
    echo "building and running $base..."
    mkdir -p "$top/build-$base"
    build "$src_base" "$top/build-$base"
    outputs "$top/build-$base" "$out_base"
    touch "$out_base/done"
fi
[[ "${HDIMESH_BITWISE_BASE_ONLY:-0}" == 1 ]] && { echo "base outputs in $out_base"; exit 0; }
echo "building and running the working tree..."
mkdir -p "$here/build-head"
build "$PWD" "$here/build-head"
outputs "$here/build-head" "$here/out-head"

status=0
for f in $(cd "$out_base" && find . -type f ! -name bench_surface.txt ! -name done | sort); do
    if ! cmp -s "$out_base/$f" "$here/out-head/$f"; then
        echo "DIFFERS: ${f#./}"
        status=1
    fi
done
if [[ $status -eq 0 ]]; then echo "BITWISE OK"; else echo "BITWISE DIFFERENT"; fi
exit $status
