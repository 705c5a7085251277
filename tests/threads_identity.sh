#!/usr/bin/env bash
# adapt with 1, 2, 3 and 8 threads writes the same bytes: the work is cut by the mesh, never by
# the thread count (common/parallel.h). Fails naming the first count whose output differs.
#   tests/threads_identity.sh ADAPT OUT_DIR NAME INPUT [adapt options...]
set -euo pipefail
adapt=$1 out=$2 name=$3 input=$4
shift 4
mkdir -p "$out"
for n in 1 2 3 8; do
    "$adapt" "$input" -o "$out/$name.t$n.mesh" -v 0 --threads "$n" "$@"
done
for n in 2 3 8; do
    if ! cmp "$out/$name.t1.mesh" "$out/$name.t$n.mesh"; then
        echo "threads_identity: $name: --threads $n differs from --threads 1" >&2
        exit 1
    fi
done
echo "threads_identity: $name: 1, 2, 3 and 8 threads byte-identical"
