#!/usr/bin/env bash
# The PETSc adaptor on 1 and 2 ranks (issue 44): the box of tests/petsc/adapt_box.c adapted
# at several sizes, isotropic, anisotropic and uniform, with and without jittered inner
# vertices, then data/box_with_ball.msh (tests/petsc/adapt_file.c: a curved closed interface,
# which one rank's run remeshes in its surface pass and a rank's piece does not), with and
# without that pass on one rank; Markdown tables of tets, min Qe and min Qe in the metric (the
# shape the adaptation works on), the 2-rank differences, and the wall seconds of each run
# (mpiexec start-up included). Build with -DHDIMESH_BUILD_PETSC=ON -DHDIMESH_BUILD_TESTS=ON, then
#   bench/petsc_ranks.sh [BUILD_DIR] [--quick]
# As root, OpenMPI needs OMPI_ALLOW_RUN_AS_ROOT=1 and OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 (set here).
set -euo pipefail
build=${1:-build}
box=$build/tests/petsc_adapt_box
file=$build/tests/petsc_adapt_file
ball=$(dirname "$0")/../data/box_with_ball.msh
lib=$build/apps/petsc/libhdimesh_petsc.so
[[ -x $box && -x $file && -f $lib ]] ||
    { echo "petsc_ranks.sh: no $box, $file or $lib: build with PETSc and tests" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
sizes=(0.12 0.1 0.08 0.06)
[[ ${2:-} == --quick ]] && sizes=(0.12 0.1)
# prints "tets qe metric_qe seconds"
run() {
    local start end line
    start=$(date +%s.%N)
    line=$("$@" -dll_append "$lib" -dm_adaptor hdimesh 2>&1 | grep '^adapted:') ||
        { echo "error"; return; }
    end=$(date +%s.%N)
    sed -E 's/^adapted: ([0-9]+) tets, min Qe ([0-9.]+), in the metric ([0-9.]+),.*/\1 \2 \3/' \
        <<< "$line" | tr '\n' ' '
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f\n", b - a }'
}
# row LABEL PROGRAM OPTION...: one table row, 1 rank against 2
row() {
    local label=$1 program=$2 t1 q1 m1 s1 t2 q2 m2 s2
    shift 2
    read -r t1 q1 m1 s1 <<< "$(run "$program" "$@")"
    read -r t2 q2 m2 s2 <<< "$(run mpiexec -n 2 "$program" "$@")"
    if [[ $t1 == error || $t2 == error ]]; then
        echo "| $label | $t1 | $t2 | | |"
        return
    fi
    awk -v l="$label" -v t1="$t1" -v q1="$q1" -v m1="$m1" -v s1="$s1" -v t2="$t2" -v q2="$q2" \
        -v m2="$m2" -v s2="$s2" 'BEGIN {
        printf "| %s | %d / %.3f / %.3f / %.2f | %d / %.3f / %.3f / %.2f | %+.1f %% | %+.1f %% |\n",
            l, t1, q1, m1, s1, t2, q2, m2, s2, 100 * (t2 - t1) / t1, 100 * (m2 - m1) / m1 }'
}
header() {
    echo "| $1 | 1 rank: tets / min Qe / in metric / s | 2 ranks: tets / min Qe / in metric / s | tets | min Qe in metric |"
    echo "|---|---|---|---|---|"
}
header "box: metric, h, jitter"
for metric in iso aniso uniform; do
    for h in "${sizes[@]}"; do
        for jitter in 0 0.2; do
            row "$metric, $h, $jitter" "$box" -metric "$metric" -h "$h" -jitter "$jitter"
        done
    done
done
echo
header "box_with_ball.msh: metric, h, surface pass on 1 rank"
for metric in iso uniform; do
    for h in 0.2 0.12; do
        row "$metric, $h, yes" "$file" -file "$ball" -volume_tolerance 0.1 -metric "$metric" -h "$h"
        row "$metric, $h, no" "$file" -file "$ball" -volume_tolerance 0.1 -metric "$metric" \
            -h "$h" -dm_plex_metric_no_surf
    done
done
