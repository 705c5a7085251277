# meshstat end to end. This one file has two roles:
#  - included from tests/CMakeLists.txt, it registers the tests (add_test lines below);
#  - run as `cmake -DCASE=... -P meshstat.cmake`, it runs meshstat and checks its output.
# Reference numbers for data/sphere480.mesh against case A come from the independent checker
# (/usr/bin/python3 ../shared/tools/meshstat.py data/sphere480.mesh --case A --json), copied
# here so the project does not depend on ../shared at test time.

if(NOT CMAKE_SCRIPT_MODE_FILE)
    if(TARGET meshstat)
        set(_meshstat_work ${CMAKE_CURRENT_BINARY_DIR}/meshstat_work)
        foreach(_case sphere_table sphere_json_matches_reference sphere_sol_equals_hsiz
                      svg_and_stats violations_exit_1 bad_command_lines)
            add_test(NAME meshstat_${_case}
                     COMMAND ${CMAKE_COMMAND} -DCASE=${_case} -DMESHSTAT=$<TARGET_FILE:meshstat>
                             -DDATA=${PROJECT_SOURCE_DIR}/data -DWORK=${_meshstat_work}/${_case}
                             -P ${CMAKE_CURRENT_LIST_FILE})
        endforeach()
    endif()
    return()
endif()

# ------------------------------------------------------------------------------------------
# script mode

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(run_meshstat out_var rc_var)
    execute_process(COMMAND ${MESHSTAT} ${ARGN}
                    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
    set(${out_var} "${out}${err}" PARENT_SCOPE)
    set(${rc_var} "${rc}" PARENT_SCOPE)
endfunction()

function(expect_match text regex)
    if(NOT text MATCHES "${regex}")
        message(FATAL_ERROR "expected /${regex}/ in:\n${text}")
    endif()
endfunction()

function(expect_equal actual expected what)
    if(NOT "${actual}" STREQUAL "${expected}")
        message(FATAL_ERROR "${what}: got '${actual}', expected '${expected}'")
    endif()
endfunction()

set(SPHERE ${DATA}/sphere480.mesh)

if(CASE STREQUAL "sphere_table")
    run_meshstat(out rc ${SPHERE})
    expect_equal("${rc}" 0 "exit code")
    expect_match("${out}" "\nvertices +156\n")
    expect_match("${out}" "\ntets +483\n")
    expect_match("${out}" "\nedges +766\n")
    expect_match("${out}" "\nboundary triangles +256  \\(stored triangles 256\\)\n")
    expect_match("${out}" "no size field")
    expect_match("${out}" "\ncheck: clean\n")
    # the volume equals the volume the boundary encloses (both printed to 9 decimals)
    string(REGEX MATCH "\nvolume +([0-9.]+)  \\(enclosed ([0-9.]+)\\)" _ "${out}")
    expect_equal("${CMAKE_MATCH_1}" "4.007149580" "volume")
    expect_equal("${CMAKE_MATCH_2}" "${CMAKE_MATCH_1}" "enclosed volume")

elseif(CASE STREQUAL "sphere_json_matches_reference")
    run_meshstat(out rc ${SPHERE} --bench-field A --json)
    expect_equal("${rc}" 0 "exit code")
    foreach(pair "vertices=156" "tets=483" "boundary_triangles=256" "edges=766" "clean=ON")
        string(REPLACE "=" ";" pair "${pair}")
        list(GET pair 0 key)
        list(GET pair 1 expected)
        string(JSON value GET "${out}" ${key})
        expect_equal("${value}" "${expected}" "${key}")
    endforeach()
    # floats: our value starts with the reference's first ten significant digits
    foreach(pair "min_qe=0.2582916042" "mean_qe=0.6375618507" "percent_qe_ge_05=89.64803312"
                 "min_qt=0.05320199414" "mean_qt=0.3941295848" "percent_qt_ge_066=12.27154046"
                 "percent_too_long=87.72845953" "max_length_ratio=18.79628792"
                 "min_length_ratio=0.9421817572" "mean_length_ratio=3.485443651")
        string(REPLACE "=" ";" pair "${pair}")
        list(GET pair 0 key)
        list(GET pair 1 prefix)
        string(JSON value GET "${out}" ${key})
        string(FIND "${value}" "${prefix}" at)
        if(NOT at EQUAL 0)
            message(FATAL_ERROR "${key}: got ${value}, the reference checker says ${prefix}...")
        endif()
    endforeach()
    string(JSON histogram GET "${out}" qe_histogram)
    string(REGEX REPLACE "[ \n]" "" histogram "${histogram}")
    expect_equal("${histogram}" "[0,0,6,21,23,110,180,110,29,4]" "Qe histogram")
    string(JSON histogram GET "${out}" length_ratio_histogram)
    string(REGEX REPLACE "[ \n]" "" histogram "${histogram}")
    expect_equal("${histogram}" "[0,0,0,2,14,78,141,531]" "L/hth histogram")

elseif(CASE STREQUAL "sphere_sol_equals_hsiz")
    # a constant .sol on the input mesh (a background mesh over itself) measures like --hsiz
    set(sol "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n156\n1 1\n")
    foreach(i RANGE 1 156)
        string(APPEND sol "0.3\n")
    endforeach()
    string(APPEND sol "End\n")
    file(WRITE ${WORK}/constant.sol "${sol}")
    run_meshstat(with_sol rc ${SPHERE} --sol ${WORK}/constant.sol)
    expect_equal("${rc}" 0 "exit code with --sol")
    run_meshstat(with_hsiz rc ${SPHERE} --hsiz 0.3)
    expect_equal("${rc}" 0 "exit code with --hsiz")
    expect_match("${with_sol}" "\nQt >= 0.66 +")
    foreach(row "Qt >= 0.66" "too long \\(L > 1.515 hth\\)" "Qt min / mean" "L/hth min / mean / max" "L/hth histogram")
        string(REGEX MATCH "\n${row} +[^\n]+" a "${with_sol}")
        string(REGEX MATCH "\n${row} +[^\n]+" b "${with_hsiz}")
        expect_equal("${a}" "${b}" "row ${row}")
    endforeach()

elseif(CASE STREQUAL "svg_and_stats")
    run_meshstat(out rc ${SPHERE} --bench-field C --svg ${WORK}/sphere.svg --stats ${WORK}/sphere.json)
    expect_equal("${rc}" 0 "exit code")
    file(READ ${WORK}/sphere.svg svg)
    expect_match("${svg}" "^<\\?xml")
    expect_match("${svg}" "<svg ")
    expect_match("${svg}" "</svg>\n$")
    expect_match("${svg}" "L/hth")
    file(READ ${WORK}/sphere.json stats)
    string(JSON tets GET "${stats}" tets)
    expect_equal("${tets}" 483 "tets in --stats")
    string(JSON has_size GET "${stats}" has_size)
    expect_equal("${has_size}" ON "has_size in --stats")
    file(GLOB leftovers ${WORK}/*.tmp*)
    expect_equal("${leftovers}" "" "temporary files left")

elseif(CASE STREQUAL "violations_exit_1")
    # one tet whose bottom face (1 3 2) is missing from Triangles: a hole in the boundary
    file(WRITE ${WORK}/open.mesh "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTriangles\n3\n2 3 4 1\n1 4 3 1\n1 2 4 1\nTetrahedra\n1\n1 2 3 4 0\nEnd\n")
    run_meshstat(out rc ${WORK}/open.mesh)
    expect_equal("${rc}" 1 "exit code")
    expect_match("${out}" "\ntets +1\n")
    expect_match("${out}" "check: 4 violations: missing_boundary_triangle 1 open_boundary_edge 3")
    run_meshstat(out rc ${WORK}/open.mesh --json)
    expect_equal("${rc}" 1 "exit code with --json")
    string(FIND "${out}" "{" brace)
    string(SUBSTRING "${out}" ${brace} -1 json)
    string(REGEX REPLACE "}\n.*" "}" json "${json}")
    string(JSON count GET "${json}" violations)
    expect_equal("${count}" 4 "violations in JSON")

elseif(CASE STREQUAL "bad_command_lines")
    run_meshstat(out rc ${WORK}/does_not_exist.mesh)
    expect_equal("${rc}" 1 "missing file")
    expect_match("${out}" "^meshstat: error: [^\n]*does_not_exist.mesh")
    run_meshstat(out rc ${SPHERE} --frobnicate)
    expect_equal("${rc}" 2 "unknown flag")
    run_meshstat(out rc ${SPHERE} --hsiz 0.1 --bench-field A)
    expect_equal("${rc}" 2 "two size fields")
    run_meshstat(out rc ${SPHERE} --bench-field Q)
    expect_equal("${rc}" 1 "unknown benchmark case")
    expect_match("${out}" "expected A, B, C, D or E")
    run_meshstat(out rc)
    expect_equal("${rc}" 2 "no input")

else()
    message(FATAL_ERROR "unknown CASE '${CASE}'")
endif()
