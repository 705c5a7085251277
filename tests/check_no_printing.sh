#!/usr/bin/env bash
# Fails when a library source writes to stdout or stderr: the library hands its lines to the
# caller's MessageSink (common/messages.h) and the apps print them. volume/tools/ (a build-time
# generator) may print. Prints one line per offending use (file:line: text) and exits 1.
#   tests/check_no_printing.sh SOURCE_DIR
set -uo pipefail
root=${1:?usage: check_no_printing.sh SOURCE_DIR}
cd "$root" || exit 2
pattern='std::(cout|cerr|clog)|\b(printf|fprintf|puts|fputs|putchar|perror|vprintf|vfprintf)[[:space:]]*\(|\b(stdout|stderr)\b'
# each line with its comment dropped ("//" to the end) before the match
found=$(grep -rsnE "$pattern" common hdi volume surface coupling --include='*.h' --include='*.cpp' \
            --include='*.inc' | grep -v '^volume/tools/' |
        while IFS= read -r hit; do
            code=${hit#*:*:}
            code=${code%%//*}
            [[ $code =~ $pattern ]] && echo "$hit"
        done)
if [[ -n $found ]]; then
    echo "$found"
    echo "the library may not print: hand the line to a MessageSink (common/messages.h)"
    exit 1
fi
echo "no library source prints"
