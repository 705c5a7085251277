# Drop-in for Mmg scripts: adapt and surfremesh run mmg3d's and mmgs's documented command lines
# (-in/-out/-sol, -hausd -hgrad, -hmax, -hmin, -hsiz, -ar, -nr, -optim, -noinsert -noswap
# -nomove, -nosurf, the default X.o.mesh) on tiny inputs; each output passes an independent
# check (tests/mmg_cli_check.py) and obeys its flags; a refused Mmg flag is one error line, a
# non-zero exit and no file. (`! cmd` would not stop `set -e`: exit codes are tested.)
if(NOT EXISTS /usr/bin/python3)
    return()
endif()
set(mmg_out ${CMAKE_CURRENT_BINARY_DIR}/mmg_cli_out)
set(mmg_check "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/mmg_cli_check.py")
# The size rule's bound: no edge longer than H/0.66 once no edge is too long (size_quality.h).
set(mmg_long 0.455)   # for H = 0.3
set(mmg_long2 0.304)  # for H = 0.2

# mmg_cli_test(NAME APP SCRIPT): SCRIPT (bash, $APP the tool) in a fresh directory of its own
# holding in.mesh: sphere480 for adapt, icosphere320 as a Medit surface for surfremesh.
function(mmg_cli_test name app script)
    set(dir ${mmg_out}/${name})
    if(app STREQUAL "adapt")
        set(input "cp ${PROJECT_SOURCE_DIR}/data/sphere480.mesh in.mesh")
    else()
        set(input "${mmg_check} medit ${PROJECT_SOURCE_DIR}/data/icosphere320.obj in.mesh")
    endif()
    add_test(NAME mmg_cli_${name}
             COMMAND bash -c "set -e; rm -rf ${dir}; mkdir -p ${dir}; cd ${dir}; ${input}; APP=$<TARGET_FILE:${app}>; ${script}")
endfunction()

# mmg3d (adapt)
mmg_cli_test(mmg3d_hausd_hgrad adapt
    "$APP -in in.mesh -out out.mesh -hausd 0.01 -hgrad 1.3 -v 0; ${mmg_check} check out.mesh --tets")
mmg_cli_test(mmg3d_hmax_default_output adapt
    "$APP -in in.mesh -hmax 0.3 -hausd 0.05 -v 0; ${mmg_check} check in.o.mesh --tets --max-edge ${mmg_long}")
# Mmg's "filein fileout" positionals; -hmin floors the -hsiz below it (half of it is the shortest
# edge the size rule leaves: -hsiz 0.2 alone makes 0.11)
mmg_cli_test(mmg3d_hmin adapt
    "$APP in.mesh out.mesh -hsiz 0.2 -hmin 0.35 -hausd 0.05 -v 0; ${mmg_check} check out.mesh --tets --min-edge 0.175")
mmg_cli_test(mmg3d_hsiz_nosurf adapt
    "$APP -in in.mesh -out out.mesh -hsiz 0.3 -nosurf -hgrad -1 -v 0; ${mmg_check} check out.mesh --tets --max-edge ${mmg_long}")
mmg_cli_test(mmg3d_sol adapt
    "${mmg_check} sol in.mesh sizes.sol 0.3; $APP -in in.mesh -sol sizes.sol -out out.mesh -hausd 0.05 -v 0; ${mmg_check} check out.mesh --tets --max-edge ${mmg_long}")
mmg_cli_test(mmg3d_met adapt
    "${mmg_check} sol in.mesh sizes.sol 0.3; $APP -in in.mesh -met sizes.sol -out out.mesh -hausd 0.05 -v 0; ${mmg_check} check out.mesh --tets --max-edge ${mmg_long}")
# no -sol: Mmg reads X.sol beside X.mesh, and so do we (saying so)
mmg_cli_test(mmg3d_default_sol adapt
    "${mmg_check} sol in.mesh in.sol 0.3; $APP in.mesh -hausd 0.05 -v 1 > log.txt 2>&1; grep -q 'sizes from in.sol' log.txt; ${mmg_check} check in.o.mesh --tets --max-edge ${mmg_long}")
# -ar 10 makes every edge of the sphere's 256 boundary triangles a ridge, which the surface pass
# keeps; -nr turns the detection off again
mmg_cli_test(mmg3d_ridge_angle adapt
    "$APP -in in.mesh -out out.mesh -hsiz 0.3 -hausd 0.05 -ar 10 > log.txt; grep -q 'surface: 256 triangles -> 256,' log.txt; ${mmg_check} check out.mesh --tets; $APP -in in.mesh -out nr.mesh -hsiz 0.3 -hausd 0.05 -ar 10 -nr > nr.txt; if grep -q 'surface: 256 triangles -> 256,' nr.txt; then exit 1; fi; ${mmg_check} check nr.mesh --tets")
mmg_cli_test(mmg3d_optim adapt
    "$APP -in in.mesh -out out.mesh -optim -v 0; ${mmg_check} check out.mesh --tets --at-most-vertices-of in.mesh")
mmg_cli_test(mmg3d_noinsert_noswap_nomove adapt
    "$APP -in in.mesh -out out.mesh -hsiz 0.3 -noinsert -noswap -nomove -nreg -v 0; ${mmg_check} check out.mesh --tets --same-vertices-as in.mesh")
# an input without extension is IN.mesh (Mmg tries IN.meshb first); -v -1 is silent; an -out
# without extension takes the input's
mmg_cli_test(mmg3d_names_and_verbosity adapt
    "$APP in -hsiz 0.3 -hausd 0.05 -v -1 > log.txt; test ! -s log.txt; ${mmg_check} check in.o.mesh --tets; $APP -v -in in.mesh -out res -hsiz 0.3 -hausd 0.05 > /dev/null; ${mmg_check} check res.mesh --tets")
# refused: one line naming the flag, exit code 2, nothing written
mmg_cli_test(mmg3d_refused adapt
    "for f in -ls -lssurf -isoref -rmc -lag -opnbdy -nofem -optimLES -octree -rn -nsd -xreg -nosizreq -hgradreq -d -val -default -f; do rc=0; $APP -in in.mesh -out out.mesh -hsiz 0.3 $f 1 2> err.txt || rc=$?; test $rc -eq 2; test $(wc -l < err.txt) -eq 1; grep -q -- \"^adapt: error: $f (.*) is an Mmg option hdimesh does not support\" err.txt; test ! -e out.mesh; done; rc=0; $APP -in in.mesh -out out.mesh -hsiz 0.3 -noout 2> err.txt || rc=$?; test $rc -ne 0; grep -q \"unknown option '-noout'\" err.txt; test ! -e out.mesh")
# a tensor .sol is a metric, as Mmg reads it (-A or not); OUT.sol holds the metric at the output
mmg_cli_test(mmg3d_anisotropic_sol adapt
    "${mmg_check} sol in.mesh aniso.sol 0.3 --tensor; $APP -in in.mesh -sol aniso.sol -out out.mesh -hgrad -1 -v 0; ${mmg_check} check out.mesh --tets; grep -A2 SolAtVertices out.sol | tail -1 | grep -q '^1 3'; $APP -in in.mesh -sol aniso.sol -out a.mesh -A -v 0; ${mmg_check} check a.mesh --tets")
mmg_cli_test(mmg3d_parameter_file adapt
    "touch in.mmg3d; rc=0; $APP -in in.mesh -out out.mesh -hsiz 0.3 2> err.txt || rc=$?; test $rc -ne 0; grep -q 'in.mmg3d: an Mmg parameter file' err.txt; test ! -e out.mesh")
mmg_cli_test(mmg3d_help adapt
    "$APP --help > help.txt; grep -qF -- '--hsiz X | -hsiz X' help.txt; grep -qF -- 'IN | -in IN' help.txt; grep -qF -- 'OUT | -o OUT | -out OUT' help.txt; grep -qF -- '--sol S | -sol S | -met S' help.txt; grep -qF -- '--no-ridges | -nr' help.txt; grep -qF -- '-ls  level-set discretization' help.txt")

# mmgs (surfremesh)
mmg_cli_test(mmgs_hausd_hgrad surfremesh
    "$APP -in in.mesh -out out.mesh -hausd 0.01 -hgrad 1.3 -v 0; ${mmg_check} check out.mesh")
mmg_cli_test(mmgs_hmax_default_output surfremesh
    "$APP -in in.mesh -hmax 0.2 -v 0; ${mmg_check} check in.o.mesh --max-edge ${mmg_long2}")
# -hmin floors the sizes of a .sol (0.1 alone: shortest edge 0.063, with -hmin 0.2: 0.12); the
# refinement to the distance tolerance is not bound by it (see README)
mmg_cli_test(mmgs_hmin surfremesh
    "${mmg_check} sol in.mesh sizes.sol 0.1; $APP in.mesh out.mesh -sol sizes.sol -hmin 0.2 -v 0; ${mmg_check} check out.mesh --min-edge 0.1")
mmg_cli_test(mmgs_hsiz surfremesh
    "$APP -in in.mesh -out out.mesh -hsiz 0.2 -v 0; ${mmg_check} check out.mesh --max-edge ${mmg_long2}")
mmg_cli_test(mmgs_sol surfremesh
    "${mmg_check} sol in.mesh sizes.sol 0.2; $APP -in in.mesh -sol sizes.sol -out out.mesh -v 0; ${mmg_check} check out.mesh --max-edge ${mmg_long2}")
mmg_cli_test(mmgs_ridge_angle surfremesh
    "$APP -in in.mesh -out out.mesh -hsiz 0.3 -ar 10 > log.txt; grep -q 'features: [1-9][0-9]* ridge edges' log.txt; ${mmg_check} check out.mesh; $APP -in in.mesh -out nr.mesh -hsiz 0.3 -ar 10 -nr > nr.txt; grep -q 'features: 0 ridge edges' nr.txt; ${mmg_check} check nr.mesh")
mmg_cli_test(mmgs_optim surfremesh
    "$APP -in in.mesh -out out.mesh -optim -v 0; ${mmg_check} check out.mesh")
# -noinsert: no vertex more or less; with -noswap -nomove nothing may change at all; -nreg (normal
# regularization) is what the model always does
mmg_cli_test(mmgs_noinsert surfremesh
    "$APP -in in.mesh -out out.mesh -hsiz 0.1 -noinsert -v 0; ${mmg_check} check out.mesh --same-vertices-as in.mesh; $APP -in in.mesh -out still.mesh -hsiz 0.1 -noinsert -noswap -nomove -nreg -v 0; ${mmg_check} check still.mesh --same-vertices-as in.mesh --unmoved")
mmg_cli_test(mmgs_refused surfremesh
    "for f in -ls -lssurf -isoref -rmc -keep-ref -rn -nsd -xreg -nosizreq -hgradreq -d -val -default -f; do rc=0; $APP -in in.mesh -out out.mesh -hsiz 0.3 $f 2> err.txt || rc=$?; test $rc -eq 2; test $(wc -l < err.txt) -eq 1; grep -q -- \"^surfremesh: error: $f (.*) is an Mmg option hdimesh does not support\" err.txt; test ! -e out.mesh; done; rc=0; $APP -in in.mesh -out out.mesh -nosurf 2> err.txt || rc=$?; test $rc -ne 0; grep -q \"unknown option '-nosurf'\" err.txt; test ! -e out.mesh")
mmg_cli_test(mmgs_help surfremesh
    "$APP --help > help.txt; grep -qF -- '--hsiz X | -hsiz X' help.txt; grep -qF -- '--ridge-angle X | -ar X' help.txt; grep -qF -- '--optim | -optim' help.txt; grep -qF -- '--noswap | -noswap' help.txt")

# -m caps the address space: a run needing more stops with one line and writes nothing. Not in a
# sanitizer build, whose shadow memory is reserved beyond any such cap (the tools refuse -m there).
if(NOT HDIMESH_SANITIZE)
    mmg_cli_test(mmg3d_memory_limit adapt
        "rc=0; $APP -in in.mesh -out out.mesh -hsiz 0.03 -m 30 -v 0 2> err.txt || rc=$?; test $rc -eq 1; grep -q 'exceeded the -m limit of 30 MB' err.txt; test ! -e out.mesh; $APP -in in.mesh -out ok.mesh -hsiz 0.3 -hausd 0.05 -m 500 -v 0; ${mmg_check} check ok.mesh --tets")
    mmg_cli_test(mmgs_memory_limit surfremesh
        "rc=0; $APP -in in.mesh -out out.mesh -hsiz 0.005 -m 30 -v 0 2> err.txt || rc=$?; test $rc -eq 1; grep -q 'exceeded the -m limit of 30 MB' err.txt; test ! -e out.mesh")
endif()
