# The module layering (docs/architecture.md): no module includes what it may not.
add_test(NAME layering
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/check_layering.sh ${PROJECT_SOURCE_DIR})
# The check itself catches a forbidden include: surface/ including volume/, hdi/ using FLANN
# outside knn.cpp.
add_test(NAME layering_catches_forbidden_includes
         COMMAND bash -c "d=$(mktemp -d) && mkdir -p $d/surface $d/hdi && \
printf '#include \"volume/mesh/tet_mesh.h\"\\n' > $d/surface/x.cpp && \
printf '#include <vector>\\n#include <flann/flann.hpp>\\n' > $d/hdi/y.cpp && \
bash ${CMAKE_CURRENT_SOURCE_DIR}/check_layering.sh $d; echo rc=$?; rm -rf $d")
set_tests_properties(layering_catches_forbidden_includes PROPERTIES PASS_REGULAR_EXPRESSION
    "surface/x.cpp:1: surface/ may not include volume/mesh/tet_mesh.h\nhdi/y.cpp:2: hdi/ may not include flann/flann.hpp\nrc=1|hdi/y.cpp:2: hdi/ may not include flann/flann.hpp\nsurface/x.cpp:1: surface/ may not include volume/mesh/tet_mesh.h\nrc=1")
# ... and inside volume/, a subfolder including a sibling or a higher layer.
add_test(NAME layering_catches_volume_layers
         COMMAND bash -c "d=$(mktemp -d) && mkdir -p $d/volume/mesh $d/volume/io && \
printf '#include \"volume/optimize/smooth.h\"\\n' > $d/volume/mesh/x.cpp && \
printf '#include \"volume/mesh/tet_mesh.h\"\\n#include \"volume/check/check.h\"\\n' > $d/volume/io/y.cpp && \
bash ${CMAKE_CURRENT_SOURCE_DIR}/check_layering.sh $d; echo rc=$?; rm -rf $d")
set_tests_properties(layering_catches_volume_layers PROPERTIES PASS_REGULAR_EXPRESSION
    "volume/mesh/x.cpp:1: volume/mesh/ may not include volume/optimize/smooth.h\nvolume/io/y.cpp:2: volume/io/ may not include volume/check/check.h\nrc=1|volume/io/y.cpp:2: volume/io/ may not include volume/check/check.h\nvolume/mesh/x.cpp:1: volume/mesh/ may not include volume/optimize/smooth.h\nrc=1")
# The library never prints (common/messages.h): no library source writes to stdout or stderr.
add_test(NAME library_never_prints
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/check_no_printing.sh ${PROJECT_SOURCE_DIR})
# The check itself catches a print.
add_test(NAME library_never_prints_catches_a_print
         COMMAND bash -c "d=$(mktemp -d) && mkdir -p $d/volume && \
printf 'void f() { std::printf(\"x\"); }  // printf\\n' > $d/volume/x.cpp && \
bash ${CMAKE_CURRENT_SOURCE_DIR}/check_no_printing.sh $d; echo rc=$?; rm -rf $d")
set_tests_properties(library_never_prints_catches_a_print PROPERTIES PASS_REGULAR_EXPRESSION
    "volume/x.cpp:1:.*rc=1")
