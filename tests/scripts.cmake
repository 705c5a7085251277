# Script and app-level tests: every tests/cmake/*.cmake fragment adds its own add_test() lines,
# so each area registers its end-to-end checks without touching a shared file.
file(GLOB fragments CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/cmake/*.cmake")
foreach(fragment ${fragments})
    include(${fragment})
endforeach()
