# The deal.II example (examples/dealii/, docs/dealii.md), built against tetray installed in
# ${TETRAY_EXAMPLES_PREFIX} (fixture examples_prefix) and Debian's deal.II 9.4 (libdeal.ii-dev,
# installed by scripts/setup.sh). Without deal.II one test fails and says so: the suite does not
# pass without these tests.
if(TETRAY_SANITIZE)
  return()  # the example would have to be built with the sanitizers too (as adaptor_outside_project)
endif()

# deal.II's package file defines many variables: looked for in a function, they stay in it.
function(tetray_find_dealii found)
  find_package(deal.II 9.4 QUIET)
  set(${found} ${deal.II_FOUND} PARENT_SCOPE)
endfunction()
tetray_find_dealii(dealii_found)
if(NOT dealii_found)
  add_test(NAME examples_dealii_missing COMMAND ${CMAKE_COMMAND}
    "-DMESSAGE=deal.II 9.4 was not found when tetray was configured, so the deal.II example's tests could not be registered: install libdeal.ii-dev (scripts/setup.sh does) and configure again"
    -P ${CMAKE_CURRENT_SOURCE_DIR}/fail_with_message.cmake)
  set_tests_properties(examples_dealii_missing PROPERTIES LABELS "examples;dealii")
  return()
endif()

# The checks run with Debian's Python, which has numpy and python3-png (test packages).
set(dealii_python ${TETRAY_PYTHON_EXECUTABLE})
if(NOT dealii_python)
  set(dealii_python /usr/bin/python3)
endif()
set(dealii_example ${PROJECT_SOURCE_DIR}/examples/dealii)
set(dealii_work ${CMAKE_CURRENT_BINARY_DIR}/dealii)
set(dealii_solver ${dealii_work}/build/dealii_heat_insitu)

# Configure and build the example against the installed prefix (one translation unit of deal.II
# code: about a minute on 2 cores).
add_test(NAME examples_dealii_build COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${dealii_example}
  -DBUILD_DIR=${dealii_work}/build -DPREFIX=${TETRAY_EXAMPLES_PREFIX}
  -P ${CMAKE_CURRENT_SOURCE_DIR}/dealii_build.cmake)
set_tests_properties(examples_dealii_build PROPERTIES LABELS "examples;dealii;install"
  TIMEOUT 900 FIXTURES_REQUIRED examples_prefix FIXTURES_SETUP dealii_solver)

# The runs, each in its own working directory (the config writes to out/dealii_heat there); the
# old outputs go first (the log appends).
set(dealii_runs np1 np2 np3 np2_without_ghost_flags np3_without_ghost_flags np2_wide_source
  np2_fixed_mesh)
list(TRANSFORM dealii_runs PREPEND ${dealii_work}/ OUTPUT_VARIABLE dealii_run_dirs)
file(MAKE_DIRECTORY ${dealii_run_dirs})
list(TRANSFORM dealii_run_dirs APPEND /out OUTPUT_VARIABLE dealii_outputs)
add_test(NAME examples_dealii_clean COMMAND ${CMAKE_COMMAND} -E rm -rf ${dealii_outputs})
set_tests_properties(examples_dealii_clean PROPERTIES LABELS "examples;dealii"
  FIXTURES_SETUP dealii_clean)

# tetray_dealii_run(NAME NP [ARG...]): test examples_dealii_NAME, the example with ARGs on NP ranks
# in ${dealii_work}/NAME.
function(tetray_dealii_run name np)
  set(test examples_dealii_${name})
  if(np EQUAL 1)
    add_test(NAME ${test} COMMAND ${dealii_solver} ${ARGN})
  else()
    tetray_add_mpi_test(${test} ${np} ${dealii_solver} ${ARGN})
  endif()
  set_tests_properties(${test} PROPERTIES WORKING_DIRECTORY ${dealii_work}/${name}
    LABELS "mpi;examples;dealii" TIMEOUT 120 FIXTURES_REQUIRED "dealii_solver;dealii_clean"
    FIXTURES_SETUP dealii_runs)
endfunction()
tetray_dealii_run(np1 1)
tetray_dealii_run(np2 2)
tetray_dealii_run(np3 3)
tetray_dealii_run(np2_without_ghost_flags 2 --without-ghost-flags)
tetray_dealii_run(np3_without_ghost_flags 3 --without-ghost-flags)
tetray_dealii_run(np2_wide_source 2 --source-width 0.1)
tetray_dealii_run(np2_fixed_mesh 2 --refine-every 0)

# tetray_dealii_compare(NAME RUN [ARG...]): test NAME, compare_runs.py with ARGs on the images of
# the one-rank run and of RUN.
function(tetray_dealii_compare name run)
  add_test(NAME ${name} COMMAND ${dealii_python}
    ${PROJECT_SOURCE_DIR}/tests/python/compare_runs.py ${dealii_work}/np1/out/dealii_heat
    ${dealii_work}/${run}/out/dealii_heat --min-images 12 ${ARGN})
  set_tests_properties(${name} PROPERTIES LABELS "examples;dealii" TIMEOUT 60
    FIXTURES_REQUIRED dealii_runs)
endfunction()
# The same bytes on 1, 2 and 3 ranks: the meshes are refined alike on any partition, and each
# rank's ghost cells (flagged) complete the cells around its own.
tetray_dealii_compare(examples_dealii_np2_same_images np2 --scene isotherms --scene layers)
tetray_dealii_compare(examples_dealii_np3_same_images np3 --scene isotherms --scene layers)
# What the comparisons can see. Without the ghost flags each ghost cell is drawn by two ranks:
# the transparent images differ from the one-rank ones in 1504-3865 pixels (2 ranks) and
# 1775-4968 (3 ranks) of their 49,152; with a wider source every image differs, in 2503-11,099.
# (p4est partitions alike from run to run: the counts repeat.)
tetray_dealii_compare(examples_dealii_np2_without_ghost_flags_differs np2_without_ghost_flags
  --scene layers --differ-by 500)
tetray_dealii_compare(examples_dealii_np3_without_ghost_flags_differs np3_without_ghost_flags
  --scene layers --differ-by 500)
tetray_dealii_compare(examples_dealii_wide_source_differs np2_wide_source
  --scene isotherms --scene layers --differ-by 1000)

# tetray_dealii_rebuilds(NAME RUN REFINE_EVERY [PASS_REGEX]): test NAME, dealii_rebuilds.py on
# RUN's log for an adaptation every REFINE_EVERY steps; with PASS_REGEX the check must fail with
# that message instead.
function(tetray_dealii_rebuilds name run refine_every)
  add_test(NAME ${name} COMMAND ${dealii_python}
    ${CMAKE_CURRENT_SOURCE_DIR}/dealii_rebuilds.py ${dealii_work}/${run}/out/dealii_heat/tetray_log.csv
    --refine-every ${refine_every} --steps 24)
  set_tests_properties(${name} PROPERTIES LABELS "examples;dealii" TIMEOUT 60
    FIXTURES_REQUIRED dealii_runs)
  if(ARGN)
    set_tests_properties(${name} PROPERTIES PASS_REGULAR_EXPRESSION "${ARGN}")
  endif()
endfunction()
# The BVH is rebuilt after each adaptation (every 3rd step, by default), and only then.
foreach(run np1 np2 np3)
  tetray_dealii_rebuilds(examples_dealii_${run}_rebuilds ${run} 3)
endforeach()
tetray_dealii_rebuilds(examples_dealii_fixed_mesh_rebuilds np2_fixed_mesh 0)
# What the log check can see: the run whose mesh never changes has no rebuild where one adapting
# every 3rd step must have, and an adapting run rebuilds where a fixed mesh would only refit.
tetray_dealii_rebuilds(examples_dealii_fixed_mesh_lacks_rebuilds np2_fixed_mesh 3
  "step 4: field_refit, expected rebuild")
tetray_dealii_rebuilds(examples_dealii_np1_rebuilds_unexpected np1 0
  "step 4: rebuild, expected field_refit")
