# The install tree works for a downstream find_package(hdimesh) project.
add_test(NAME install_consumer
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/install_consumer.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR})
# Installs sanitized libraries would need the sanitizer runtime in the consumer too.
set_tests_properties(install_consumer PROPERTIES LABELS no-sanitizer)
