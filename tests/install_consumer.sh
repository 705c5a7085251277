#!/usr/bin/env bash
# Installs the build tree (every component) into a scratch prefix, and once more into a scratch
# DESTDIR, and checks that nothing lands outside them; that only public headers went there and
# that they are self-contained; then configures, builds and runs tests/consumer against it with
# find_package(hdimesh), and imports the installed Python package and adapts with it.
#   install_consumer.sh BUILD_DIR SOURCE_DIR [PYTHON_DIR PYTHON]
# PYTHON_DIR: HDIMESH_PYTHON_INSTALL_DIR when the module is built (relative: under the prefix).
set -euo pipefail
build_dir=$1
source_dir=$2
python_dir=${3:-}
python=${4:-/usr/bin/python3}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# every "-- Installing: P" / "-- Up-to-date: P" line of cmake --install's log names a path under $2
only_under() {
    local log=$1 root=$2 outside
    outside=$(grep -E '^-- (Installing|Up-to-date): ' "$log" | sed -E 's/^-- [A-Za-z-]+: //' \
              | grep -v "^$root/" || true)
    if [[ -n "$outside" ]]; then
        echo "installed outside $root:"; echo "$outside"; exit 1
    fi
    grep -qE '^-- (Installing|Up-to-date): ' "$log" || { echo "nothing installed into $root"; exit 1; }
}

component=()
if [[ "$python_dir" == /* ]]; then
    # an absolute package dir is the user's choice to leave the prefix: the C++ part only
    echo "HDIMESH_PYTHON_INSTALL_DIR=$python_dir is absolute: checking the C++ component only"
    component=(--component Unspecified)
    python_dir=""
fi
prefix=$scratch/prefix
cmake --install "$build_dir" --prefix "$prefix" "${component[@]}" > "$scratch/prefix.log"
only_under "$scratch/prefix.log" "$prefix"
# DESTDIR with the configured prefix: a packager's staged install
DESTDIR=$scratch/root cmake --install "$build_dir" "${component[@]}" > "$scratch/destdir.log"
only_under "$scratch/destdir.log" "$scratch/root"

# Public headers only: nothing from a detail/ folder, and every project header an installed
# header includes is installed too.
include_dir=$prefix/include/hdimesh
if find "$include_dir" -path '*/detail/*' | grep -q .; then
    echo "private headers installed:"; find "$include_dir" -path '*/detail/*'; exit 1
fi
missing=0
while IFS=: read -r header target; do
    if [[ ! -f "$include_dir/$target" ]]; then
        echo "${header#"$include_dir"/} includes $target, which is not installed"
        missing=1
    fi
done < <(grep -rhoE '^#include "(common|hdi|volume|surface|coupling)/[^"]+"' "$include_dir" \
         --include='*.h' -H | sed -E 's/^([^:]*):#include "([^"]*)"/\1:\2/')
[[ $missing -eq 0 ]] || exit 1
cmake -S "$source_dir/tests/consumer" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$scratch/build" > /dev/null
"$scratch/build/consumer"

if [[ -n "$python_dir" ]]; then
    # from / so neither the source nor the build tree's package can be the one imported
    (cd / && PYTHONPATH="$prefix/$python_dir" "$python" -c '
import sys, hdimesh
assert hdimesh.__file__.startswith(sys.argv[1]), hdimesh.__file__
out = hdimesh.adapt(hdimesh.read(sys.argv[2]), hsiz=0.3)
print("installed python package:", hdimesh.__file__, len(out.tets), "tets")
' "$prefix/" "$source_dir/data/sphere480.mesh")
fi
