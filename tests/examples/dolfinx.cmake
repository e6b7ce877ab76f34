# The DOLFINx example, run with the system Python against the installed package (fixture
# examples_prefix), as a user runs it.
if(NOT TARGET tetray_python OR TETRAY_SANITIZE)
  return()
endif()
set(TETRAY_EXAMPLE_PYTHON_ENV
  PYTHONPATH=${TETRAY_EXAMPLES_PREFIX}/${TETRAY_PYTHON_INSTALL_DIR}:${PROJECT_SOURCE_DIR}/examples/dolfinx
  PYTHONDONTWRITEBYTECODE=1 XDG_CACHE_HOME=${TETRAY_DOLFINX_CACHE})

# The DOLFINx example (examples/dolfinx/heat_insitu.py) on one, two and three ranks, each in its own
# working directory (the config writes to out/ there), then their images compared byte for byte:
# the opaque scene and the transparent one, where a ghost tet drawn twice would show. Without the
# ghost flags (--without ghost) the 2- and 3-rank images of the transparent scene must differ
# from the one-rank images: the runs show that the flags matter, and the tests fail if they stop
# mattering. (The tet ids change no pixel of these scenes: docs/coupling.md "DOLFINx".)
# First the old images and the form cache go, and one short run compiles the forms: DOLFINx
# processes that find a form being compiled by another wait only 10 s for it.
set(heat_example ${PROJECT_SOURCE_DIR}/examples/dolfinx/heat_insitu.py)
set(heat_runs ${CMAKE_CURRENT_BINARY_DIR}/dolfinx_heat)
set(heat_run_names np1 np2 np3 np2_without_ghost np3_without_ghost)
list(TRANSFORM heat_run_names PREPEND ${heat_runs}/ OUTPUT_VARIABLE heat_run_dirs)
file(MAKE_DIRECTORY ${heat_run_dirs} ${heat_runs}/compile)
list(TRANSFORM heat_run_dirs APPEND /out OUTPUT_VARIABLE heat_outputs)
add_test(NAME python_dolfinx_clean COMMAND ${CMAKE_COMMAND} -E rm -rf ${heat_outputs}
  ${heat_runs}/np2/vtk ${heat_runs}/replay ${TETRAY_DOLFINX_CACHE})
set_tests_properties(python_dolfinx_clean PROPERTIES LABELS python
  FIXTURES_SETUP dolfinx_clean)
add_test(NAME python_dolfinx_compile COMMAND ${TETRAY_PYTHON_EXECUTABLE} ${heat_example}
  --steps 1 WORKING_DIRECTORY ${heat_runs}/compile)
set_tests_properties(python_dolfinx_compile PROPERTIES LABELS python TIMEOUT 300
  ENVIRONMENT "${TETRAY_EXAMPLE_PYTHON_ENV}" FIXTURES_REQUIRED "dolfinx_clean;examples_prefix"
  FIXTURES_SETUP dolfinx_forms)

# tetray_dolfinx_heat_run(NAME NP [ARG...]): test python_dolfinx_heat_NAME, the example with ARGs
# on NP ranks in ${heat_runs}/NAME.
function(tetray_dolfinx_heat_run name np)
  set(test python_dolfinx_heat_${name})
  if(np EQUAL 1)
    add_test(NAME ${test} COMMAND ${TETRAY_PYTHON_EXECUTABLE} ${heat_example} ${ARGN})
  else()
    tetray_add_mpi_test(${test} ${np} ${TETRAY_PYTHON_EXECUTABLE} ${heat_example} ${ARGN})
  endif()
  set_tests_properties(${test} PROPERTIES WORKING_DIRECTORY ${heat_runs}/${name}
    LABELS "mpi;python" TIMEOUT 300 ENVIRONMENT "${TETRAY_EXAMPLE_PYTHON_ENV}"
    FIXTURES_REQUIRED "dolfinx_forms;examples_prefix" FIXTURES_SETUP dolfinx_heat_runs)
endfunction()
tetray_dolfinx_heat_run(np1 1)
tetray_dolfinx_heat_run(np2 2 --vtk vtk)
tetray_dolfinx_heat_run(np3 3)
tetray_dolfinx_heat_run(np2_without_ghost 2 --without ghost)
tetray_dolfinx_heat_run(np3_without_ghost 3 --without ghost)

# tetray_dolfinx_heat_compare(NAME RUN [ARG...]): test NAME, compare_runs.py with ARGs on the
# images of the one-rank run and of RUN.
function(tetray_dolfinx_heat_compare name run)
  add_test(NAME ${name} COMMAND ${TETRAY_PYTHON_EXECUTABLE}
    ${PROJECT_SOURCE_DIR}/tests/python/compare_runs.py ${heat_runs}/np1/out/dolfinx_heat
    ${heat_runs}/${run}/out/dolfinx_heat --min-images 4 ${ARGN})
  set_tests_properties(${name} PROPERTIES LABELS python TIMEOUT 60
    ENVIRONMENT "${TETRAY_EXAMPLE_PYTHON_ENV}" FIXTURES_REQUIRED dolfinx_heat_runs)
endfunction()
tetray_dolfinx_heat_compare(python_dolfinx_heat_same_images np2
  --scene temperature --scene layers)
tetray_dolfinx_heat_compare(python_dolfinx_heat_np3_same_images np3
  --scene temperature --scene layers)
# At least 50 of the 192 x 144 pixels per image. Seen over 6 runs: 215-1070 on 2 ranks,
# 322-1511 on 3 (DOLFINx's partitioner cuts the box a little differently from run to run).
tetray_dolfinx_heat_compare(python_dolfinx_heat_np2_without_ghost_differs np2_without_ghost
  --scene layers --differ-by 50)
tetray_dolfinx_heat_compare(python_dolfinx_heat_np3_without_ghost_differs np3_without_ghost
  --scene layers --differ-by 50)

# The series the two-rank run saved as DOLFINx writes it (Lagrange tets, ghost cells and ghost
# points, one .pvtu of two pieces per step), replayed on one rank with the same config: the same
# images, byte for byte, as in situ.
add_test(NAME python_dolfinx_replay COMMAND $<TARGET_FILE:tetray-replay>
  -c ${PROJECT_SOURCE_DIR}/examples/dolfinx/heat_insitu.yaml --first-step 1
  --output ${heat_runs}/replay ${heat_runs}/np2/vtk/temperature.pvd)
set_tests_properties(python_dolfinx_replay PROPERTIES LABELS python TIMEOUT 120
  FIXTURES_REQUIRED dolfinx_heat_runs FIXTURES_SETUP dolfinx_replay)
add_test(NAME python_dolfinx_replay_same_images COMMAND ${TETRAY_PYTHON_EXECUTABLE}
  ${PROJECT_SOURCE_DIR}/tests/python/compare_runs.py ${heat_runs}/np2/out/dolfinx_heat
  ${heat_runs}/replay --scene temperature --scene layers --min-images 4)
set_tests_properties(python_dolfinx_replay_same_images PROPERTIES LABELS python TIMEOUT 60
  ENVIRONMENT "${TETRAY_EXAMPLE_PYTHON_ENV}" FIXTURES_REQUIRED dolfinx_replay)
