#!/usr/bin/env bash
# The adaptor on 2 ranks against 1, with adapt_box.c or adapt_file.c (PROGRAM): the 2-rank
# result is the same bits on a rerun, its tet count within PERCENT of the 1-rank one, and its
# min Qe in the metric (Qe itself for a size) no more than PERCENT below the 1-rank one.
#   ranks_compare.sh MPIEXEC PROGRAM LIBHDIMESH_PETSC METRIC PERCENT [OPTION...]
set -euo pipefail
mpiexec=$1 box=$2 lib=$3 metric=$4 percent=$5
shift 5
options=("$@")
run() { "$@" -dll_append "$lib" -dm_adaptor hdimesh -metric "$metric" "${options[@]}" | grep '^adapted:'; }
one=$(run "$box")
two=$(run "$mpiexec" -n 2 "$box")
again=$(run "$mpiexec" -n 2 "$box")
echo "1 rank:  $one"
echo "2 ranks: $two"
[[ "$two" == "$again" ]] || { echo "2 ranks: a rerun differs: $again"; exit 1; }
tets() { sed -E 's/^adapted: ([0-9]+) tets.*/\1/' <<< "$1"; }
qe() { sed -E 's/.*in the metric ([0-9.]+),.*/\1/' <<< "$1"; }
awk -v a="$(tets "$one")" -v b="$(tets "$two")" -v qa="$(qe "$one")" -v qb="$(qe "$two")" \
    -v percent="$percent" 'BEGIN {
        d = 100 * (b - a) / a; dq = 100 * (qb - qa) / qa
        printf "tets %+.1f %%, min Qe in the metric %.3f against %.3f (%+.1f %%)\n", d, qb, qa, dq
        if (d > percent || d < -percent) { print "tet count off by more than " percent " %"; exit 1 }
        if (dq < -percent) { print "min Qe more than " percent " % below one rank'"'"'s"; exit 1 } }'
