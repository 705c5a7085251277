#!/usr/bin/env bash
# Fails when a module includes what the layering forbids (docs/architecture.md):
#   common/   std, Eigen (the point type)    hdi/     common/, Eigen, FLANN (in hdi/knn.cpp only)
#   volume/   common/, Eigen                 surface/ common/, hdi/, OpenMesh, Eigen
#   coupling/ every module                   apps/    every module, through the library API
# Inside volume/ every file lives in a subfolder, and the subfolders are layered: a subfolder may
# include its own headers and those of the layers below it, never a sibling's or a higher one's.
#   0 mesh/      the container, local numbering, topology, predicates, (the SizeField interface is common/size_field.h)
#   1 io/  check/  size/      file formats; the checker and reports; the concrete size fields
#   2 refine/  optimize/  fill/   the 239-pattern refinement; the optimization operators; the
#                                 cavity filler and advancing front
# Prints one line per forbidden include (file:line: the include) and exits 1 when there is any.
#   tests/check_layering.sh SOURCE_DIR
set -uo pipefail
root=${1:?usage: check_layering.sh SOURCE_DIR}
cd "$root" || exit 2

allowed_modules() {
    case $1 in
        common) echo "common" ;;
        hdi) echo "common hdi" ;;
        volume) echo "common volume" ;;
        surface) echo "common hdi surface" ;;
        coupling) echo "common hdi volume surface coupling" ;;
    esac
}
allowed_libraries() {  # third-party include prefixes a module may use
    case $1 in
        common) echo "Eigen" ;;
        hdi) echo "Eigen flann" ;;
        volume) echo "Eigen" ;;
        surface) echo "Eigen OpenMesh" ;;
        coupling) echo "Eigen OpenMesh" ;;
    esac
}

volume_layer() {  # layer=the layer of volume/ subfolder $1 (header above), empty when none
    case $1 in
        mesh) layer=0 ;;
        io|check|size) layer=1 ;;
        refine|optimize|fill) layer=2 ;;
        *) layer= ;;
    esac
}

bad=0
for module in common hdi volume surface coupling; do
    [[ -d $module ]] || continue
    modules=" $(allowed_modules "$module") "
    libraries=" $(allowed_libraries "$module") "
    while IFS=: read -r file line text; do
        # (a bash match, not a sed per line: thousands of includes)
        [[ $text =~ include[[:space:]]*[\<\"]([^\>\"]*)[\>\"] ]] || continue
        target=${BASH_REMATCH[1]}
        first=${target%%/*}
        label=$module
        [[ $first == "$target" ]] && continue  # a system header (<vector>) or a local one
        case $first in
            common|hdi|volume|surface|coupling|apps)
                if [[ $modules == *" $first "* ]]; then
                    [[ $module == volume && $first == volume ]] || continue
                    # volume/ includes volume/: its subfolder's layer must be below (or the same
                    # subfolder)
                    from=${file#volume/}
                    from=${from%%/*}
                    to=${target#volume/}
                    to=${to%%/*}
                    volume_layer "$from"
                    from_layer=$layer
                    volume_layer "$to"
                    to_layer=$layer
                    label=volume/$from
                    if [[ -n $from_layer && -n $to_layer ]] &&
                        { [[ $from == "$to" ]] || ((to_layer < from_layer)); }; then
                        continue
                    fi
                fi ;;
            Eigen|flann|OpenMesh)
                if [[ $libraries == *" $first "* ]]; then
                    [[ $first == flann && $file != hdi/knn.cpp ]] || continue
                fi ;;
            *) continue ;;  # other system headers (sys/, ...)
        esac
        echo "$file:$line: $label/ may not include $target"
        bad=1
    done < <(grep -rnE '^[[:space:]]*#[[:space:]]*include' "$module" --include='*.h' --include='*.cpp' --include='*.inc' \
             | grep -v '^[^:]*/tools/')
done
exit $bad
