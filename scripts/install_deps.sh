#!/usr/bin/env bash
# Installs the Debian packages hdimesh needs, only those missing (apt-get; run as root or with sudo).
#   scripts/install_deps.sh          build dependencies
#   scripts/install_deps.sh --tests  plus what the test suite uses (third-party readers)
set -euo pipefail

packages=(g++ cmake make libopenmesh-dev libeigen3-dev libflann-dev doctest-dev)
# the Python module (python/): pybind11 and the interpreter's headers; numpy at run time,
# meshio for its example
packages+=(pybind11-dev python3-dev python3-numpy python3-meshio)
# `pip install .` builds the module through setup.py with Debian's setuptools and wheel
packages+=(python3-setuptools python3-wheel)
if [[ "${1:-}" == "--tests" ]]; then
    # meshio and gmsh read our outputs back as independent third-party readers;
    # numpy/scipy serve the independent checker scripts.
    # clang-format checks the tree against .clang-format.
    # pytest runs the Python module's tests; venv and pip the `pip install .` test (pip_install_venv).
    packages+=(python3 python3-numpy python3-scipy python3-meshio python3-pytest gmsh clang-format)
    packages+=(python3-venv python3-pip)
    # the PETSc adaptor (apps/petsc) and its C and petsc4py tests; OpenMPI comes with it
    packages+=(petsc-dev python3-petsc4py)
fi

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "installing: ${missing[*]}"
sudo=""
[[ $(id -u) -ne 0 ]] && sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
