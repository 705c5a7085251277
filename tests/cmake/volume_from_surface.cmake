# adapt on a surface input, end to end. Like meshstat.cmake, this file has two roles:
#  - included from tests/CMakeLists.txt, it registers the tests;
#  - run as `cmake -DCASE=... -P volume_from_surface.cmake`, it runs adapt, then meshstat on
#    what adapt wrote, and checks both.

if(NOT CMAKE_SCRIPT_MODE_FILE)
    if(TARGET adapt AND TARGET meshstat)
        set(_vfs_work ${CMAKE_CURRENT_BINARY_DIR}/volume_from_surface_work)
        foreach(_case sphere sphere_keep_surface spot bunny_refused overlap_refused
                      surface_flags_on_a_tet_mesh)
            add_test(NAME adapt_surface_${_case}
                     COMMAND ${CMAKE_COMMAND} -DCASE=${_case} -DADAPT=$<TARGET_FILE:adapt>
                             -DMESHSTAT=$<TARGET_FILE:meshstat> -DDATA=${PROJECT_SOURCE_DIR}/data
                             -DWORK=${_vfs_work}/${_case} -P ${CMAKE_CURRENT_LIST_FILE})
        endforeach()
    endif()
    return()
endif()

# ------------------------------------------------------------------------------------------
# script mode

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(run out_var rc_var)
    execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
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

# adapt IN -o WORK/out.mesh ARGS..., then meshstat on the output: both must succeed, the
# checker must find it clean; the meshstat table is returned.
function(mesh_and_check table_var input)
    run(out rc ${ADAPT} ${input} -o ${WORK}/out.mesh --check ${ARGN})
    expect_equal("${rc}" 0 "adapt exit code (output:\n${out})")
    expect_match("${out}" "check output: clean")
    run(table rc ${MESHSTAT} ${WORK}/out.mesh)
    expect_equal("${rc}" 0 "meshstat exit code (output:\n${table})")
    expect_match("${table}" "\ncheck: clean\n")
    # the volume equals the volume the boundary encloses
    string(REGEX MATCH "\nvolume +([0-9.]+)  \\(enclosed ([0-9.]+)\\)" _ "${table}")
    expect_equal("${CMAKE_MATCH_2}" "${CMAKE_MATCH_1}" "enclosed volume")
    file(GLOB leftovers ${WORK}/*.tmp*)
    expect_equal("${leftovers}" "" "temporary files left")
    set(${table_var} "${table}" PARENT_SCOPE)
endfunction()

# adapt must fail with exit code 1, print `regex`, and leave no output file.
function(expect_refusal input regex)
    run(out rc ${ADAPT} ${input} -o ${WORK}/none.mesh ${ARGN})
    expect_equal("${rc}" 1 "adapt exit code (output:\n${out})")
    expect_match("${out}" "${regex}")
    if(EXISTS ${WORK}/none.mesh)
        message(FATAL_ERROR "adapt refused the input but wrote ${WORK}/none.mesh")
    endif()
    file(GLOB leftovers ${WORK}/*)
    expect_equal("${leftovers}" "" "files left in ${WORK}")
endfunction()

if(CASE STREQUAL "sphere")
    # the unit icosphere (320 triangles) remeshed to 0.2 and filled
    mesh_and_check(table ${DATA}/icosphere320.obj --hsiz 0.2)
    expect_match("${table}" "\ntets +[1-9][0-9]+\n")
    string(REGEX MATCH "\nvolume +([0-9.]+)" _ "${table}")
    if(CMAKE_MATCH_1 LESS 3.9 OR CMAKE_MATCH_1 GREATER 4.19)
        message(FATAL_ERROR "volume ${CMAKE_MATCH_1}: the unit ball's is 4.19")
    endif()

elseif(CASE STREQUAL "sphere_keep_surface")
    # the 320 triangles are the boundary, as given
    mesh_and_check(table ${DATA}/icosphere320.obj --hsiz 0.3 --keep-surface)
    expect_match("${table}" "\nboundary triangles +320  \\(stored triangles 320\\)\n")

elseif(CASE STREQUAL "spot")
    # the README's example: a new user's command line (2 % of the bounding-box diagonal)
    mesh_and_check(table ${DATA}/spot.obj --hsiz 0.05)

elseif(CASE STREQUAL "bunny_refused")
    # the Stanford bunny has five holes in its base: named, and nothing written
    expect_refusal(${DATA}/stanford-bunny.obj
                   "stanford-bunny.obj: the surface is open: 5 boundary loops \\(loop 1: [0-9]+ edges through vertices [0-9]+, "
                   --hsiz 0.01)

elseif(CASE STREQUAL "overlap_refused")
    # two unit icospheres, the second moved by half a radius: they cross each other
    expect_refusal(${DATA}/overlapping_spheres.obj
                   "overlapping_spheres.obj: the surface intersects itself: [0-9]+ pairs of triangles meet \\(triangles [0-9]+ and [0-9]+; "
                   --hsiz 0.2)

elseif(CASE STREQUAL "surface_flags_on_a_tet_mesh")
    run(out rc ${ADAPT} ${DATA}/sphere480.mesh -o ${WORK}/none.mesh --hsiz 0.3 --keep-surface)
    expect_equal("${rc}" 2 "--keep-surface on a tet mesh")
    expect_match("${out}" "apply to a surface input")
    run(out rc ${ADAPT} ${DATA}/sphere480.mesh -o ${WORK}/none.mesh --hausd 0.01)
    expect_equal("${rc}" 2 "--hausd on a tet mesh")
    if(EXISTS ${WORK}/none.mesh)
        message(FATAL_ERROR "a refused command wrote ${WORK}/none.mesh")
    endif()

else()
    message(FATAL_ERROR "unknown CASE '${CASE}'")
endif()
