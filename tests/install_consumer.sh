#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, checks that only public headers went there and
# that they are self-contained, then configures, builds and runs tests/consumer against it with
# find_package(hdimesh).
set -euo pipefail
build_dir=$1
source_dir=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# the C++ library only: the Python package goes to the interpreter's site-packages
cmake --install "$build_dir" --prefix "$scratch/prefix" --component Unspecified > /dev/null

# Public headers only: nothing from a detail/ folder, and every project header an installed
# header includes is installed too.
include_dir=$scratch/prefix/include/hdimesh
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
cmake -S "$source_dir/tests/consumer" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" \
    -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$scratch/build" > /dev/null
"$scratch/build/consumer"
