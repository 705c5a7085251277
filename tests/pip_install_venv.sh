#!/usr/bin/env bash
# The README's `pip install` works offline: a fresh venv of Debian's python3 (with its numpy),
# pip install --no-build-isolation --no-index of the source tree (setup.py builds _hdimesh with
# CMake), then the venv imports hdimesh and adapts. Exits 77 (skipped) without venv/pip/setuptools.
#   pip_install_venv.sh SOURCE_DIR WORK_DIR
set -euo pipefail
source_dir=$1
work_dir=$2
python=/usr/bin/python3
if ! "$python" -c 'import ensurepip, venv, setuptools, wheel' 2> /dev/null; then
    echo "skipped: needs python3-venv python3-pip python3-setuptools python3-wheel"; exit 77
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
venv=$scratch/venv
"$python" -m venv --system-site-packages "$venv"
# setuptools' scratch (with the CMake tree) in the test's folder: the source tree stays clean and
# a rerun rebuilds incrementally
export HDIMESH_BUILD_BASE=$work_dir/pip_build
export PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_NO_INPUT=1
"$venv/bin/pip" install --no-build-isolation --no-index "$source_dir"
# what the wheel held: the package and the native module
files=$("$venv/bin/pip" show -f hdimesh)
grep -qE '^ +hdimesh/__init__\.py$' <<< "$files" || { echo "no hdimesh/__init__.py"; echo "$files"; exit 1; }
grep -qE '^ +hdimesh/_hdimesh[^/]*\.so$' <<< "$files" || { echo "no _hdimesh*.so"; echo "$files"; exit 1; }
# from / so neither the source nor a build tree's package can be the one imported
cd / && "$venv/bin/python" -c '
import sys, hdimesh
assert hdimesh.__file__.startswith(sys.argv[1]), hdimesh.__file__
out = hdimesh.adapt(hdimesh.read(sys.argv[2]), hsiz=0.3)
print("venv package:", hdimesh.__file__, len(out.tets), "tets")
' "$venv/" "$source_dir/data/sphere480.mesh"
