# The module layering (docs/architecture.md): no module includes what it may not.
add_test(NAME layering
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/check_layering.sh ${PROJECT_SOURCE_DIR})
# The check itself catches a forbidden include: surface/ including volume/, hdi/ using FLANN
# outside knn.cpp.
add_test(NAME layering_catches_forbidden_includes
         COMMAND bash -c "d=$(mktemp -d) && mkdir -p $d/surface $d/hdi && \
printf '#include \"volume/tet_mesh.h\"\\n' > $d/surface/x.cpp && \
printf '#include <vector>\\n#include <flann/flann.hpp>\\n' > $d/hdi/y.cpp && \
bash ${CMAKE_CURRENT_SOURCE_DIR}/check_layering.sh $d; echo rc=$?; rm -rf $d")
set_tests_properties(layering_catches_forbidden_includes PROPERTIES PASS_REGULAR_EXPRESSION
    "surface/x.cpp:1: surface/ may not include volume/tet_mesh.h\nhdi/y.cpp:2: hdi/ may not include flann/flann.hpp\nrc=1|hdi/y.cpp:2: hdi/ may not include flann/flann.hpp\nsurface/x.cpp:1: surface/ may not include volume/tet_mesh.h\nrc=1")
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
