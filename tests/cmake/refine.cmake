# Bisection refinement (issue 3): the committed pattern table must be exactly what the generator
# writes (the generator also re-proves every entry and exits non-zero on any failure).
if(TARGET generate_refine_patterns)
    add_test(NAME refine_patterns_table_regenerates
        COMMAND sh -c "\"$1\" \"$2\" && cmp \"$2\" \"$3\"" refine_patterns_table_regenerates
            $<TARGET_FILE:generate_refine_patterns>
            ${CMAKE_CURRENT_BINARY_DIR}/refine_patterns_table.regenerated.inc
            ${PROJECT_SOURCE_DIR}/volume/refine_patterns_table.inc)
endif()
