# The install tree works for a downstream find_package(hdimesh) project, and for Python; an
# install with --prefix or DESTDIR writes nothing outside it.
set(install_python_args)
if(TARGET _hdimesh)
    set(install_python_args ${HDIMESH_PYTHON_INSTALL_DIR} ${Python3_EXECUTABLE})
endif()
add_test(NAME install_consumer
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/install_consumer.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR}
                 ${install_python_args})
# Installs sanitized libraries would need the sanitizer runtime in the consumer too.
set_tests_properties(install_consumer PROPERTIES LABELS no-sanitizer)
