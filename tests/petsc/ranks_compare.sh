#!/usr/bin/env bash
# The adaptor on 2 ranks against 1, on the box of adapt_box.c: the 2-rank result is the same
# bits on a rerun, its tet count within TETS_PERCENT of the 1-rank one, its min Qe above a
# floor; both min Qe are printed (the 1-rank boxes are lattices: docs/tuning.md).
#   ranks_compare.sh MPIEXEC ADAPT_BOX LIBHDIMESH_PETSC METRIC TETS_PERCENT MIN_QE_FLOOR [OPTION...]
set -euo pipefail
mpiexec=$1 box=$2 lib=$3 metric=$4 percent=$5 floor=$6
shift 6
run() { "$@" -dll_append "$lib" -dm_adaptor hdimesh -metric "$metric" "${options[@]}" | grep '^adapted:'; }
options=("$@")
one=$(run "$box")
two=$(run "$mpiexec" -n 2 "$box")
again=$(run "$mpiexec" -n 2 "$box")
echo "1 rank:  $one"
echo "2 ranks: $two"
[[ "$two" == "$again" ]] || { echo "2 ranks: a rerun differs: $again"; exit 1; }
tets() { sed -E 's/^adapted: ([0-9]+) tets.*/\1/' <<< "$1"; }
qe() { sed -E 's/.*min Qe ([0-9.]+),.*/\1/' <<< "$1"; }
awk -v a="$(tets "$one")" -v b="$(tets "$two")" -v qa="$(qe "$one")" -v qb="$(qe "$two")" \
    -v floor="$floor" -v percent="$percent" 'BEGIN {
        d = 100 * (b - a) / a; printf "tets %+.1f %%, min Qe %.3f against %.3f\n", d, qb, qa;
        if (d > percent || d < -percent) { print "tet count off by more than " percent " %"; exit 1 }
        if (qb < floor) { print "min Qe under " floor; exit 1 } }'
