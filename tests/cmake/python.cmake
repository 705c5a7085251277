# The Python module (python/): pytest on tests/python (the app's case A reproduced, callable
# sizes, the GIL released, each bad input), the examples/ scripts, and an install of the
# package (into a scratch DESTDIR) that imports and runs, and the README's pip install in a venv.
if(TARGET _hdimesh AND TARGET adapt AND EXISTS /usr/bin/python3)
    set(python_env PYTHONPATH=${PROJECT_BINARY_DIR}/python HDIMESH_DATA=${PROJECT_SOURCE_DIR}/data
        HDIMESH_ADAPT=$<TARGET_FILE:adapt>)
    add_test(NAME python_module
             COMMAND /usr/bin/python3 -m pytest -q -p no:cacheprovider ${PROJECT_SOURCE_DIR}/tests/python)
    set_tests_properties(python_module PROPERTIES ENVIRONMENT "${python_env}")
    add_test(NAME python_example
             COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/examples/adapt_gmsh_mesh.py
                     ${PROJECT_SOURCE_DIR}/data/box_with_ball.msh ${CMAKE_CURRENT_BINARY_DIR}/box_with_ball.vtu --fine 0.08)
    set_tests_properties(python_example PROPERTIES ENVIRONMENT "${python_env}"
                         PASS_REGULAR_EXPRESSION "wrote .*box_with_ball.vtu")
    add_test(NAME python_example_loop
             COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/examples/solve_adapt_transfer.py)
    set_tests_properties(python_example_loop PROPERTIES ENVIRONMENT "${python_env}"
                         PASS_REGULAR_EXPRESSION "round 3: [0-9]+ tets")
    # a relative HDIMESH_PYTHON_INSTALL_DIR is under the prefix
    set(python_install_dir ${HDIMESH_PYTHON_INSTALL_DIR})
    if(NOT IS_ABSOLUTE "${python_install_dir}")
        set(python_install_dir ${CMAKE_INSTALL_PREFIX}/${python_install_dir})
    endif()
    add_test(NAME python_install
             COMMAND bash -c "rm -rf ${CMAKE_CURRENT_BINARY_DIR}/python_root && DESTDIR=${CMAKE_CURRENT_BINARY_DIR}/python_root cmake --install ${PROJECT_BINARY_DIR} --component python > /dev/null && cd / && PYTHONPATH=${CMAKE_CURRENT_BINARY_DIR}/python_root${python_install_dir} /usr/bin/python3 -c \"import hdimesh, sys; m = hdimesh.read(sys.argv[1]); print(hdimesh.__file__, len(hdimesh.adapt(m, hsiz=0.3).tets))\" ${PROJECT_SOURCE_DIR}/data/sphere480.mesh")
    set_tests_properties(python_install PROPERTIES PASS_REGULAR_EXPRESSION "python_root.*hdimesh/__init__.py [0-9]+")
    # The README's `pip install` in a fresh venv, offline: it compiles the library again (a few
    # minutes on 2 cores, with both of them), so it is labelled pip for -LE pip.
    add_test(NAME pip_install_venv
             COMMAND bash ${PROJECT_SOURCE_DIR}/tests/pip_install_venv.sh ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR})
    set_tests_properties(pip_install_venv PROPERTIES LABELS "pip;no-sanitizer" TIMEOUT 2400
                         PROCESSORS 2 SKIP_RETURN_CODE 77 PASS_REGULAR_EXPRESSION "venv package: .*hdimesh/__init__.py [0-9]+ tets")
endif()
