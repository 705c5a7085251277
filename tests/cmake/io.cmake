# Mesh I/O end to end (volume/io/tet_io.h): Debian's meshio and the gmsh CLI read what meshconvert
# writes (.mesh .meshb .msh 2.2/4.1 ASCII/binary .vtu) with the same counts and refs, our reader
# reads Gmsh's own meshes, and meshconvert's error contract holds. The test command installs
# python3-meshio and gmsh beforehand; this test installs nothing.
if(TARGET meshconvert)
    add_test(NAME io_third_party_readers
             COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/third_party_readers.py
                     $<TARGET_FILE:meshconvert> ${PROJECT_SOURCE_DIR}/data)
endif()
