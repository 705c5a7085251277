#!/usr/bin/env bash
# Checks that every tracked C++ file follows the project's .clang-format; prints the files that
# do not and exits 1. `scripts/check_format.sh --fix` reformats them in place.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=(--dry-run --Werror)
[[ "${1:-}" == "--fix" ]] && mode=(-i)
mapfile -t files < <(git ls-files '*.h' '*.cpp')
bad=()
for f in "${files[@]}"; do
    clang-format "${mode[@]}" "$f" > /dev/null 2>&1 || bad+=("$f")
done
if [[ ${#bad[@]} -gt 0 ]]; then
    printf 'not formatted (scripts/check_format.sh --fix): %s\n' "${bad[@]}"
    exit 1
fi
echo "format: ${#files[@]} files follow .clang-format"
