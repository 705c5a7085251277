# Hostile files through every app (tests/fuzz_apps.py): mutants of small valid inputs in each
# format, no crash, no hang, one error line and no output file on a refusal. 200 per format in the
# assertions build; fewer elsewhere, to keep .ci/run's three builds under 30 minutes.
if(EXISTS /usr/bin/python3 AND TARGET adapt AND TARGET surfremesh AND TARGET meshconvert
   AND TARGET meshstat)
    if(HDIMESH_SANITIZE)
        set(fuzz_mutants 15)
    elseif(HDIMESH_ASSERTS)
        set(fuzz_mutants 200)
    else()
        set(fuzz_mutants 50)  # the assertions build runs the same code, checked, on 200
    endif()
    add_test(NAME fuzz_apps
             COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/fuzz_apps.py
                     $<TARGET_FILE_DIR:adapt> ${CMAKE_CURRENT_BINARY_DIR}/fuzz_apps
                     --mutants ${fuzz_mutants})
    set_tests_properties(fuzz_apps PROPERTIES TIMEOUT 900 PASS_REGULAR_EXPRESSION " 0 failures")
endif()
