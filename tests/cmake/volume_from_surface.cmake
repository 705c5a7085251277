# adapt on a surface input, end to end. Like meshstat.cmake, this file has two roles:
#  - included from tests/CMakeLists.txt, it registers the tests;
#  - run as `cmake -DCASE=... -P volume_from_surface.cmake`, it runs adapt, then meshstat on
#    what adapt wrote, and checks both.

if(NOT CMAKE_SCRIPT_MODE_FILE)
    if(TARGET adapt AND TARGET meshstat)
        set(_vfs_work ${CMAKE_CURRENT_BINARY_DIR}/volume_from_surface_work)
        set(_vfs_whole)
        foreach(_model fandisk spot rocker-arm cheburashka)
            list(APPEND _vfs_whole whole_${_model}_raw whole_${_model}_remeshed)
        endforeach()
        foreach(_case sphere sphere_keep_surface spot bunny overlap_refused
                      surface_flags_on_a_tet_mesh ${_vfs_whole})
            add_test(NAME adapt_surface_${_case}
                     COMMAND ${CMAKE_COMMAND} -DCASE=${_case} -DADAPT=$<TARGET_FILE:adapt>
                             -DMESHSTAT=$<TARGET_FILE:meshstat> -DDATA=${PROJECT_SOURCE_DIR}/data
                             -DWORK=${_vfs_work}/${_case} -P ${CMAKE_CURRENT_LIST_FILE})
        endforeach()
        # whole real models: minutes under the sanitizers, so Release builds only
        foreach(_case ${_vfs_whole})
            set_tests_properties(adapt_surface_${_case} PROPERTIES LABELS no-sanitizer)
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

elseif(CASE MATCHES "^whole_(.+)_(raw|remeshed)$")
    # The shared models whole: raw (their triangles kept, the interior at 2 % of the bounding-box
    # diagonal) and remeshed at 1 % of it (fandisk 7.6156, spot 2.5881, rocker-arm 1.1650,
    # cheburashka 1.2739).
    set(model ${CMAKE_MATCH_1})
    set(mode ${CMAKE_MATCH_2})
    set(size_fandisk_raw 0.152312)
    set(size_fandisk_remeshed 0.076156)
    set(size_spot_raw 0.051762)
    set(size_spot_remeshed 0.025881)
    set(size_rocker-arm_raw 0.0233)
    set(size_rocker-arm_remeshed 0.01165)
    set(size_cheburashka_raw 0.025478)
    set(size_cheburashka_remeshed 0.012739)
    set(h ${size_${model}_${mode}})
    if(mode STREQUAL "raw")
        mesh_and_check(table ${DATA}/${model}.obj --hsiz ${h} --keep-surface)
        file(STRINGS ${DATA}/${model}.obj faces REGEX "^f ")
        list(LENGTH faces num_faces)
        expect_match("${table}"
                     "\nboundary triangles +${num_faces}  \\(stored triangles ${num_faces}\\)\n")
    else()
        mesh_and_check(table ${DATA}/${model}.obj --hsiz ${h})
        # shape and size: the floors every remeshed model reaches (the bench has the figures)
        run(table rc ${MESHSTAT} ${WORK}/out.mesh --hsiz ${h})
        string(REGEX MATCH "\nQe >= 0.5 +([0-9.]+) %" _ "${table}")
        if(NOT CMAKE_MATCH_1 OR CMAKE_MATCH_1 LESS 99)
            message(FATAL_ERROR "Qe >= 0.5 on ${CMAKE_MATCH_1} % of the tets (at least 99):\n${table}")
        endif()
        string(REGEX MATCH "\nQt >= 0.66 +([0-9.]+) %" _ "${table}")
        if(NOT CMAKE_MATCH_1 OR CMAKE_MATCH_1 LESS 99)
            message(FATAL_ERROR "Qt >= 0.66 on ${CMAKE_MATCH_1} % of the edges (at least 99):\n${table}")
        endif()
    endif()

elseif(CASE STREQUAL "bunny")
    # the Stanford bunny has five holes in its base: with --strict named, nothing written ...
    expect_refusal(${DATA}/stanford-bunny.obj
                   "stanford-bunny.obj: the surface is open: 5 boundary loops \\(loop 1: [0-9]+ edges through vertices [0-9]+, "
                   --hsiz 0.01 --strict)
    # ... by default closed at 2 % of its diagonal, one note each, and meshed
    mesh_and_check(table ${DATA}/stanford-bunny.obj --hsiz 0.005)
    run(out rc ${ADAPT} ${DATA}/stanford-bunny.obj -o ${WORK}/out.mesh --hsiz 0.005 -v 0)
    string(REGEX MATCHALL "repaired: closed a hole of [0-9]+ edges" holes "${out}")
    list(LENGTH holes count)
    expect_equal("${count}" 5 "holes closed, one note each (output:\n${out})")

elseif(CASE STREQUAL "overlap_refused")
    # two unit icospheres, the second moved by half a radius: they cross each other
    expect_refusal(${DATA}/overlapping_spheres.obj
                   "overlapping_spheres.obj: the surface intersects itself: [0-9]+ pairs of triangles meet \\(triangles [0-9]+ and [0-9]+; "
                   --hsiz 0.2)

elseif(CASE STREQUAL "surface_flags_on_a_tet_mesh")
    run(out rc ${ADAPT} ${DATA}/sphere480.mesh -o ${WORK}/none.mesh --hsiz 0.3 --keep-surface)
    expect_equal("${rc}" 2 "--keep-surface on a tet mesh")
    expect_match("${out}" "applies to a surface input")
    if(EXISTS ${WORK}/none.mesh)
        message(FATAL_ERROR "a refused command wrote ${WORK}/none.mesh")
    endif()
    # on a tet mesh --hausd bounds the boundary's distance; alone, the sizes are the input's own
    # (Mmg's -hausd with no metric runs too)
    run(out rc ${ADAPT} ${DATA}/sphere480.mesh -o ${WORK}/hausd_only.mesh --hausd 0.05 -v 0)
    expect_equal("${rc}" 0 "--hausd alone on a tet mesh")

else()
    message(FATAL_ERROR "unknown CASE '${CASE}'")
endif()
