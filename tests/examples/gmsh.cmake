# The gmsh example (examples/gmsh/): a CAD bracket meshed by gmsh into curved 10-node tets,
# run with the system Python against the installed package (fixture examples_prefix), as a user
# runs it. gmsh comes from Debian's python3-gmsh (scripts/setup.sh); without it every test here
# fails with the example's message naming the package, none is skipped.
if(NOT TARGET tetray_python OR TETRAY_SANITIZE)
  return()
endif()
set(gmsh_env PYTHONPATH=${TETRAY_EXAMPLES_PREFIX}/${TETRAY_PYTHON_INSTALL_DIR}
  PYTHONDONTWRITEBYTECODE=1)
set(gmsh_example ${PROJECT_SOURCE_DIR}/examples/gmsh)
set(gmsh_runs ${CMAKE_CURRENT_BINARY_DIR}/gmsh_bracket)
set(gmsh_run_names np1 np2 np3)
list(TRANSFORM gmsh_run_names PREPEND ${gmsh_runs}/ OUTPUT_VARIABLE gmsh_run_dirs)
file(MAKE_DIRECTORY ${gmsh_run_dirs} ${gmsh_runs}/split)
list(TRANSFORM gmsh_run_dirs APPEND /out OUTPUT_VARIABLE gmsh_outputs)
add_test(NAME python_gmsh_clean COMMAND ${CMAKE_COMMAND} -E rm -rf ${gmsh_outputs}
  ${gmsh_runs}/split/out)
set_tests_properties(python_gmsh_clean PROPERTIES LABELS python FIXTURES_SETUP gmsh_clean)

# The example (8 steps, three scenes) on one, two and three ranks, each in its own working
# directory (the config writes to out/ there); each rank holds a share of the cells and only the
# points they use. Then the images compared byte for byte: the opaque isosurfaces, the volume
# ("x-ray") scene, whose fragments are merged across ranks, and the capped section.
function(tetray_gmsh_bracket_run name np)
  set(test python_gmsh_bracket_${name})
  if(np EQUAL 1)
    add_test(NAME ${test} COMMAND ${TETRAY_PYTHON_EXECUTABLE} ${gmsh_example}/bracket_insitu.py)
  else()
    tetray_add_mpi_test(${test} ${np} ${TETRAY_PYTHON_EXECUTABLE}
      ${gmsh_example}/bracket_insitu.py)
  endif()
  set_tests_properties(${test} PROPERTIES WORKING_DIRECTORY ${gmsh_runs}/${name}
    LABELS "mpi;python" TIMEOUT 180 ENVIRONMENT "${gmsh_env}"
    FIXTURES_REQUIRED "gmsh_clean;examples_prefix" FIXTURES_SETUP gmsh_bracket_runs)
endfunction()
tetray_gmsh_bracket_run(np1 1)
tetray_gmsh_bracket_run(np2 2)
tetray_gmsh_bracket_run(np3 3)

foreach(np 2 3)
  add_test(NAME python_gmsh_bracket_np${np}_same_images COMMAND ${TETRAY_PYTHON_EXECUTABLE}
    ${PROJECT_SOURCE_DIR}/tests/python/compare_runs.py ${gmsh_runs}/np1/out/gmsh_bracket
    ${gmsh_runs}/np${np}/out/gmsh_bracket --scene shells --scene xray --scene section
    --min-images 8)
  set_tests_properties(python_gmsh_bracket_np${np}_same_images PROPERTIES LABELS python
    TIMEOUT 60 ENVIRONMENT "${gmsh_env}" FIXTURES_REQUIRED gmsh_bracket_runs)
endforeach()

# tetray's split of the 10-node tets (level 1) against a reference that cuts each curved tet 8
# times along every edge through gmsh's own quadratic basis, in gmsh's node order (level 4,
# examples/gmsh/tet_subdivision.py), on a coarser mesh: the depth images must agree within a
# mean of 1.5e-3 of the part's size and 2% of the pixels hit by one and missed by the other
# (measured: see docs/gmsh.md). With gmsh's node order passed to tetray unchanged (its last two
# edge nodes are VTK's swapped) the check must fail.
set(gmsh_split_args ${gmsh_example}/split_study.py --size 10 --levels 1 --reference 4
  --pixels 256 --repeat 1)
add_test(NAME python_gmsh_split_against_reference COMMAND ${TETRAY_PYTHON_EXECUTABLE}
  ${gmsh_split_args} --out out/right --check 1.5e-3 0.02)
add_test(NAME python_gmsh_split_wrong_node_order_caught COMMAND ${TETRAY_PYTHON_EXECUTABLE}
  ${gmsh_split_args} --out out/wrong --check 1.5e-3 0.02 --gmsh-order)
set_tests_properties(python_gmsh_split_wrong_node_order_caught PROPERTIES
  PASS_REGULAR_EXPRESSION "level 1 is outside the check")
set_tests_properties(python_gmsh_split_against_reference python_gmsh_split_wrong_node_order_caught
  PROPERTIES WORKING_DIRECTORY ${gmsh_runs}/split LABELS python TIMEOUT 180
  ENVIRONMENT "${gmsh_env}" FIXTURES_REQUIRED "gmsh_clean;examples_prefix")
