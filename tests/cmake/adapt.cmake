# adapt end to end: runs, checks, writes; bad input gives one line, non-zero exit, no file.
set(adapt_out ${CMAKE_CURRENT_BINARY_DIR}/adapt_out)
file(MAKE_DIRECTORY ${adapt_out})
add_test(NAME adapt_app_sphere
         COMMAND adapt ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/sphere.mesh
                 --hsiz 0.3 --check --stats ${adapt_out}/sphere.json)
set_tests_properties(adapt_app_sphere PROPERTIES
    PASS_REGULAR_EXPRESSION "check output: clean")
add_test(NAME adapt_app_missing_input
         COMMAND bash -c "! $<TARGET_FILE:adapt> no_such.mesh -o ${adapt_out}/none.mesh --hsiz 1 2> ${adapt_out}/err.txt && grep -q 'no_such.mesh' ${adapt_out}/err.txt && test ! -e ${adapt_out}/none.mesh")
add_test(NAME adapt_app_needs_a_size
         COMMAND bash -c "$<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/none.mesh; test $? -ne 0 && test ! -e ${adapt_out}/none.mesh")
add_test(NAME adapt_app_conflicting_sizes
         COMMAND bash -c "$<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/none.mesh --hsiz 0.3 --bench-field A 2>&1 | grep -q 'only one of'")
# Second opinion: the independent checker (scripts/meshstat.py, numpy) on the adapted sphere.
if(EXISTS /usr/bin/python3)
    add_test(NAME adapt_app_sphere_independent_check
             COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/meshstat.py ${adapt_out}/sphere.mesh --case A)
    set_tests_properties(adapt_app_sphere_independent_check PROPERTIES
        DEPENDS adapt_app_sphere PASS_REGULAR_EXPRESSION "CONFORMING: True")
endif()
# Inputs as other meshers write them. icosphere320_tetgen.mesh is `tetgen -pgQ` (TetGen 1.5.0) of
# icosphere320: every tet face listed, the boundary inward. adapt mends it and says so in a line
# per fix-up; --strict refuses it and writes nothing.
add_test(NAME adapt_app_tetgen_input
         COMMAND bash -c "$<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/icosphere320_tetgen.mesh -o ${adapt_out}/tetgen.mesh --hsiz 0.3 --check > ${adapt_out}/tetgen.txt 2>&1 && grep -q 'dropped 722 interior triangles' ${adapt_out}/tetgen.txt && grep -q 'turned 320 boundary triangles outward' ${adapt_out}/tetgen.txt && grep -q 'check output: clean' ${adapt_out}/tetgen.txt")
add_test(NAME adapt_app_tetgen_strict
         COMMAND bash -c "! $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/icosphere320_tetgen.mesh -o ${adapt_out}/strict.mesh --hsiz 0.3 --strict 2> ${adapt_out}/strict.txt && grep -q 'interior_triangle' ${adapt_out}/strict.txt && test ! -e ${adapt_out}/strict.mesh")
# A tets-only copy of sphere480 (its Triangles section cut out) gives the same output, byte for byte.
add_test(NAME adapt_app_tets_only_input
         COMMAND bash -c "awk '/^Triangles/{skip=1; next} skip==1{n=$1; skip=2; next} skip==2{if (--n == 0) skip=0; next} {print}' ${PROJECT_SOURCE_DIR}/data/sphere480.mesh > ${adapt_out}/tets_only.mesh && ! grep -q Triangles ${adapt_out}/tets_only.mesh && $<TARGET_FILE:adapt> ${adapt_out}/tets_only.mesh -o ${adapt_out}/tets_only_out.mesh --hsiz 0.3 -v 0 2> ${adapt_out}/tets_only.txt && grep -q 'added 256 boundary triangles' ${adapt_out}/tets_only.txt && $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/with_triangles_out.mesh --hsiz 0.3 -v 0 && cmp ${adapt_out}/tets_only_out.mesh ${adapt_out}/with_triangles_out.mesh")
# A size far below the model's scale is refused up front (it would run until memory is gone),
# and so is a coordinate the geometry cannot take; neither leaves an output file.
add_test(NAME adapt_app_size_far_too_small
         COMMAND bash -c "! $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/tiny.mesh --hsiz 1e-6 2> ${adapt_out}/tiny.txt && grep -q 'far below the model' ${adapt_out}/tiny.txt && test ! -e ${adapt_out}/tiny.mesh")
add_test(NAME adapt_app_huge_coordinate
         COMMAND bash -c "sed '0,/^v /s/^v [^ ]* /v 1e308 /' ${PROJECT_SOURCE_DIR}/data/icosphere320.obj > ${adapt_out}/huge.obj && ! $<TARGET_FILE:adapt> ${adapt_out}/huge.obj -o ${adapt_out}/huge.mesh --hsiz 0.3 2> ${adapt_out}/huge.txt && grep -q 'huge.obj:[0-9]*: vertex 1e+308 exceeds' ${adapt_out}/huge.txt && test ! -e ${adapt_out}/huge.mesh")
add_test(NAME adapt_app_hausd_far_too_small
         COMMAND bash -c "! $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/tight.mesh --hsiz 0.3 --hausd 1e-300 2> ${adapt_out}/tight.txt && grep -q 'distance bound asks for' ${adapt_out}/tight.txt && test ! -e ${adapt_out}/tight.mesh")
# Two materials: box_with_ball.msh (Gmsh, box_with_ball.geo) is a ball of ref 2 inside a box of
# ref 1. The coupled pass remeshes the box's faces and the interface together, each cavity
# refilled one side at a time; the interface stays on the sphere with surfremesh's shapes.
if(EXISTS /usr/bin/python3)
    add_test(NAME adapt_app_two_materials
             COMMAND bash -c "$<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/box_with_ball.msh -o ${adapt_out}/two_materials.mesh --hsiz 0.1 --check > ${adapt_out}/two_materials.txt 2>&1 && grep -q 'surface: 1180 triangles -> .*on the input' ${adapt_out}/two_materials.txt && grep -q 'check output: clean' ${adapt_out}/two_materials.txt && /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/interface_check.py ${adapt_out}/two_materials.mesh")
endif()
# Fields carried through adapt (-field, ParMmg's spelling): a linear scalar and vector come out
# exact at every output vertex, those the projection moved outside the input included, in the
# input file's layout; a field file of the wrong vertex count is refused naming its line.
if(EXISTS /usr/bin/python3)
    add_test(NAME adapt_app_field_transfer
             COMMAND bash -c "set -e; /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/field_sol.py make ${PROJECT_SOURCE_DIR}/data/sphere480.mesh ${adapt_out}/F.sol && $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/fields.mesh --hsiz 0.3 -field ${adapt_out}/F.sol > ${adapt_out}/fields.txt && grep -q 'fields: 3 carried to' ${adapt_out}/fields.txt && /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/field_sol.py check ${adapt_out}/fields.mesh ${adapt_out}/fields.field.sol")
    add_test(NAME adapt_app_field_wrong_count
             COMMAND bash -c "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/field_sol.py make ${PROJECT_SOURCE_DIR}/data/icosphere320_tetgen.mesh ${adapt_out}/G.sol && ! $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/nofield.mesh --hsiz 0.3 --field ${adapt_out}/G.sol 2> ${adapt_out}/nofield.txt && grep -q 'G.sol:[0-9]*: SolAtVertices has' ${adapt_out}/nofield.txt && test ! -e ${adapt_out}/nofield.mesh && test ! -e ${adapt_out}/nofield.field.sol")
endif()
# Gmsh $NodeData: a .sol's fields go into a .msh output as field1..3; that file, given as
# --field of its own mesh, carries them by name into the next .msh (no side file) or, for a
# .mesh output, into OUT.field.msh; another mesh's .msh is refused naming its line.
if(EXISTS /usr/bin/python3)
    set(check_msh "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/field_sol.py check-msh")
    add_test(NAME adapt_app_field_msh
             COMMAND bash -c "set -e; cd ${adapt_out}; rm -f fm_*; /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/field_sol.py make ${PROJECT_SOURCE_DIR}/data/sphere480.mesh Fm.sol && $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o fm_in.msh --hsiz 0.35 --field Fm.sol -v 0 && ${check_msh} fm_in.msh && $<TARGET_FILE:adapt> fm_in.msh -o fm_out.msh --hsiz 0.3 --field fm_in.msh -v 0 && ${check_msh} fm_out.msh && test $(grep -c '^.NodeData' fm_out.msh) = 3 && test ! -e fm_out.field.msh && $<TARGET_FILE:adapt> fm_in.msh -o fm_out.mesh --hsiz 0.3 -field fm_in.msh -v 0 && ${check_msh} fm_out.field.msh && ! $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o fm_bad.msh --hsiz 0.3 --field fm_out.msh 2> fm_bad.txt && grep -q 'fm_out.msh:[0-9]*: .Nodes holds' fm_bad.txt && test ! -e fm_bad.msh")
endif()
# A .vtu output also carries the fields as point data, each with its component count.
if(EXISTS /usr/bin/python3)
    add_test(NAME adapt_app_field_vtu
             COMMAND bash -c "set -e; /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/field_sol.py make ${PROJECT_SOURCE_DIR}/data/sphere480.mesh ${adapt_out}/Fv.sol && $<TARGET_FILE:adapt> ${PROJECT_SOURCE_DIR}/data/sphere480.mesh -o ${adapt_out}/fields.vtu --hsiz 0.3 --field ${adapt_out}/Fv.sol -v 0 && grep -aq 'Name=\"field2\" NumberOfComponents=\"3\"' ${adapt_out}/fields.vtu && grep -aq 'Name=\"field3\" format' ${adapt_out}/fields.vtu && test -e ${adapt_out}/fields.field.sol")
endif()
