#!/usr/bin/env bash
# All tests: installs what is missing, checks the formatting, builds Release and runs CTest, then
# runs CTest again on a Release build with assertions compiled in (the incremental caches'
# cross-checks), on an AddressSanitizer + UndefinedBehaviorSanitizer build, and the threads tests
# on a ThreadSanitizer build.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
# One translation unit per batch of sources: Eigen's and OpenMesh's headers are parsed once per
# batch, a third less compile time on each of the three builds.
unity=-DCMAKE_UNITY_BUILD=ON

scripts/install_deps.sh --tests
# each stage's wall time, to keep .ci/run under its 30 minutes
stage() { echo "== $1 (at ${SECONDS} s)"; }

stage "format"
scripts/check_format.sh

stage "Release build and tests"
# every switch a stage needs is set, not taken from a cache: scripts/run_example.sh shares build/
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$unity" -DHDIMESH_BUILD_TESTS=ON \
    -DHDIMESH_BUILD_APPS=ON -DHDIMESH_BUILD_BENCH=ON -DHDIMESH_BUILD_PYTHON=ON \
    -DHDIMESH_BUILD_PETSC=ON > /dev/null
cmake --build build -j"$jobs"
stage "Release tests"
ctest --no-tests=error --test-dir build --output-on-failure -j"$jobs"

stage "Release build with assertions, and tests"
cmake -S . -B build-assert -DCMAKE_BUILD_TYPE=Release -DHDIMESH_ASSERTS=ON "$unity" \
    -DHDIMESH_BUILD_TESTS=ON -DHDIMESH_BUILD_APPS=ON \
    -DHDIMESH_BUILD_BENCH=OFF -DHDIMESH_BUILD_PYTHON=OFF -DHDIMESH_BUILD_PETSC=OFF > /dev/null
cmake --build build-assert -j"$jobs"
stage "assertions tests"
ctest --no-tests=error --test-dir build-assert --output-on-failure -j"$jobs"

stage "ASan+UBSan build and tests"
# -O1 -g1 (line tables only), as the sanitizers' docs advise: half the compile time of -O2 -g, and
# the reports still name file and line
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHDIMESH_SANITIZE=ON "$unity" \
    -DHDIMESH_BUILD_TESTS=ON -DHDIMESH_BUILD_APPS=ON \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DHDIMESH_BUILD_BENCH=OFF -DHDIMESH_BUILD_PYTHON=OFF -DHDIMESH_BUILD_PETSC=OFF > /dev/null
cmake --build build-asan -j"$jobs"
stage "ASan+UBSan tests"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --no-tests=error --test-dir build-asan --output-on-failure -j"$jobs" -LE no-sanitizer
stage "ThreadSanitizer build and the threads tests"
# only the targets those tests run (the pool's unit test, adapt at 1, 2, 3 and 8 threads): a
# few minutes, not a third full build and test run
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHDIMESH_TSAN=ON "$unity" \
    -DHDIMESH_BUILD_TESTS=ON -DHDIMESH_BUILD_APPS=ON \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DHDIMESH_BUILD_BENCH=OFF -DHDIMESH_BUILD_PYTHON=OFF -DHDIMESH_BUILD_PETSC=OFF > /dev/null
cmake --build build-tsan -j"$jobs" --target parallel_test adapt
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
    ctest --no-tests=error --test-dir build-tsan --output-on-failure -j"$jobs" -R '^(parallel_test|threads_)'
stage "done"
