# adapt end to end: runs, checks, writes; bad input gives one line, non-zero exit, no file.
set(adapt_out ${CMAKE_CURRENT_BINARY_DIR}/adapt_out)
file(MAKE_DIRECTORY ${adapt_out})
add_test(NAME adapt_app_sphere
         COMMAND adapt ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/sphere.mesh
                 --hsiz 0.3 --check --stats ${adapt_out}/sphere.json)
set_tests_properties(adapt_app_sphere PROPERTIES
    PASS_REGULAR_EXPRESSION "check output: clean")
add_test(NAME adapt_app_missing_input
         COMMAND bash -c "! $<TARGET_FILE:adapt> no_such.mesh -o ${adapt_out}/none.mesh --hsiz 1 2> ${adapt_out}/err.txt && grep -q 'no_such.mesh' ${adapt_out}/err.txt && test ! -e ${adapt_out}/none.mesh")
add_test(NAME adapt_app_needs_a_size
         COMMAND bash -c "$<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/none.mesh; test $? -ne 0 && test ! -e ${adapt_out}/none.mesh")
add_test(NAME adapt_app_conflicting_sizes
         COMMAND bash -c "$<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/none.mesh --hsiz 0.3 --bench-field A 2>&1 | grep -q 'only one of'")
# Second opinion: the independent checker (scripts/meshstat.py, numpy) on the adapted sphere.
if(EXISTS /usr/bin/python3)
    add_test(NAME adapt_app_sphere_independent_check
             COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/meshstat.py ${adapt_out}/sphere.mesh --case A)
    set_tests_properties(adapt_app_sphere_independent_check PROPERTIES
        DEPENDS adapt_app_sphere PASS_REGULAR_EXPRESSION "CONFORMING: True")
endif()
