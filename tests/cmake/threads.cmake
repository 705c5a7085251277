# The same output bytes for 1, 2, 3 and 8 threads: a sphere case (refinement and projection), a
# surface input (the fill) and a coupled case with the surface pass (fandisk's features).
set(threads_out ${CMAKE_CURRENT_BINARY_DIR}/threads_out)
file(MAKE_DIRECTORY ${threads_out})
add_test(NAME threads_identity_sphere
         COMMAND bash ${PROJECT_SOURCE_DIR}/tests/threads_identity.sh $<TARGET_FILE:adapt>
                 ${threads_out} sphere ${PROJECT_SOURCE_DIR}/data/sphere480.mesh --bench-field A --block-tets 4000)
add_test(NAME threads_identity_surface
         COMMAND bash ${PROJECT_SOURCE_DIR}/tests/threads_identity.sh $<TARGET_FILE:adapt>
                 ${threads_out} surface ${PROJECT_SOURCE_DIR}/data/icosphere320.obj --hsiz 0.15)
add_test(NAME threads_identity_coupled
         COMMAND bash ${PROJECT_SOURCE_DIR}/tests/threads_identity.sh $<TARGET_FILE:adapt>
                 ${threads_out} coupled ${PROJECT_SOURCE_DIR}/data/fandisk.msh --hsiz 0.2 --block-tets 2000)
set_tests_properties(threads_identity_sphere threads_identity_surface threads_identity_coupled
                     PROPERTIES LABELS threads)
add_test(NAME threads_app_refuses_zero
         COMMAND bash -c "! $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${threads_out}/zero.mesh --hsiz 0.3 --threads 0 2> ${threads_out}/zero.txt && grep -q -- '--threads must be at least 1' ${threads_out}/zero.txt && test ! -e ${threads_out}/zero.mesh")
