# Bisection refinement (issue 3): the committed pattern table must be exactly what the generator
# writes (the generator also re-proves every entry and exits non-zero on any failure).
if(TARGET generate_refine_patterns)
    add_test(NAME refine_patterns_table_regenerates
        COMMAND sh -c "\"$1\" \"$2\" && cmp \"$2\" \"$3\"" refine_patterns_table_regenerates
            $<TARGET_FILE:generate_refine_patterns>
            ${CMAKE_CURRENT_BINARY_DIR}/refine_patterns_table.regenerated.inc
            ${PROJECT_SOURCE_DIR}/volume/refine/refine_patterns_table.inc)
endif()

# Refinement alone end to end (issue 3's "done when", on case A to stay fast; case E is in
# bench/bench_refine): conforming output, no edge too long, the input volume to 1e-9 relative.
# 4.007149580083689 is the volume of data/sphere480.mesh.
if(TARGET adapt)
    set(refine_out ${CMAKE_CURRENT_BINARY_DIR}/refine_out)
    file(MAKE_DIRECTORY ${refine_out})
    add_test(NAME refine_adapt_case_A_refinement_only
        COMMAND sh -c "\"$1\" \"$2\" -o \"$3/A.mesh\" --bench-field A --no-optimize --no-projection --check --stats \"$3/A.json\" > \"$3/A.log\" 2>&1 && grep -q 'check output: clean' \"$3/A.log\" && grep -q 'sizes: no edge too long' \"$3/A.log\" && python3 -c \"import json,sys; s=json.load(open(sys.argv[1])); v=s['volume']; sys.exit(0 if s['percent_too_long'] == 0 and abs(v - 4.007149580083689) <= 1e-9 * 4.007149580083689 else 1)\" \"$3/A.json\""
            refine_adapt_case_A $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh ${refine_out})
endif()
