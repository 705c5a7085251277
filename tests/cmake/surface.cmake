# surfremesh end to end: the boundary of the coarse sphere (the triangles of data/sphere480.mesh,
# a Medit tet mesh whose Tetrahedra section the surface reader skips) remeshed to a uniform size,
# written as OBJ with a JSON report; a missing input and a bad option must fail cleanly.
if(TARGET surfremesh)
    add_test(NAME surfremesh_sphere
             COMMAND surfremesh ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${CMAKE_CURRENT_BINARY_DIR}/surfremesh_sphere.obj
                     --hsiz 0.15 --stats ${CMAKE_CURRENT_BINARY_DIR}/surfremesh_sphere.json -v 1)
    set_tests_properties(surfremesh_sphere PROPERTIES PASS_REGULAR_EXPRESSION "% edges Qt >= 0.66")
    add_test(NAME surfremesh_sphere_medit_out
             COMMAND surfremesh ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${CMAKE_CURRENT_BINARY_DIR}/surfremesh_sphere.mesh -v 0)
    add_test(NAME surfremesh_missing_input
             COMMAND surfremesh ${CMAKE_CURRENT_BINARY_DIR}/no-such-file.obj -o ${CMAKE_CURRENT_BINARY_DIR}/never.obj)
    set_tests_properties(surfremesh_missing_input PROPERTIES WILL_FAIL TRUE)
    add_test(NAME surfremesh_two_sizes
             COMMAND surfremesh ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${CMAKE_CURRENT_BINARY_DIR}/never.obj
                     --hsiz 0.1 --hausd 0.01)
    set_tests_properties(surfremesh_two_sizes PROPERTIES WILL_FAIL TRUE)
    # A far too small size, or a spike vertex 1e29 away, asks for more triangles than ids exist.
    add_test(NAME surfremesh_size_far_too_small
             COMMAND bash -c "! $<TARGET_FILE:surfremesh> ${PROJECT_SOURCE_DIR}/data/icosphere320.obj -o ${CMAKE_CURRENT_BINARY_DIR}/tiny.obj --hsiz 1e-7 2> ${CMAKE_CURRENT_BINARY_DIR}/tiny.txt && grep -q 'far below the model' ${CMAKE_CURRENT_BINARY_DIR}/tiny.txt && test ! -e ${CMAKE_CURRENT_BINARY_DIR}/tiny.obj")
    add_test(NAME surfremesh_spike_vertex
             COMMAND bash -c "sed '0,/^v /s/^v [^ ]* /v 1e29 /' ${PROJECT_SOURCE_DIR}/data/icosphere320.obj > ${CMAKE_CURRENT_BINARY_DIR}/spike.obj && ! $<TARGET_FILE:surfremesh> ${CMAKE_CURRENT_BINARY_DIR}/spike.obj -o ${CMAKE_CURRENT_BINARY_DIR}/spike_out.obj --hsiz 0.3 2> ${CMAKE_CURRENT_BINARY_DIR}/spike.txt && grep -q 'far below the model' ${CMAKE_CURRENT_BINARY_DIR}/spike.txt && test ! -e ${CMAKE_CURRENT_BINARY_DIR}/spike_out.obj")
    # Second opinion on the output topology and quality, where the shared checker's Python is there.
    if(EXISTS /usr/bin/python3 AND EXISTS ${PROJECT_SOURCE_DIR}/scripts/surfstat.py)
        add_test(NAME surfremesh_sphere_surfstat
                 COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/surfstat.py ${CMAKE_CURRENT_BINARY_DIR}/surfremesh_sphere.obj)
        set_tests_properties(surfremesh_sphere_surfstat PROPERTIES DEPENDS surfremesh_sphere
                             PASS_REGULAR_EXPRESSION "euler: 2")
    endif()
endif()
