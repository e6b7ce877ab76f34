# One tetray-minisolver run of the instruction-set tests (tests/render/isa/CMakeLists.txt passes
# the -D values): runs EXE on one rank (through the command prefix WRAPPER, when given) with
# TETRAY_ISA set to ISA (unset when ISA is empty) and the config CONFIG_IN with its output in
# RUN_DIR/out, and checks that it exits with EXIT_CODE (0 when not given) and that a line of its
# output ends in a match of EXPECT (a regex: the variant it ran, or why it refused). A run that
# should succeed must write IMAGES image files, every scene must hit something at the last step
# (equal empty images would prove nothing) and, given REFERENCE (the output directory of the run
# with TETRAY_ISA unset), each image must be byte for byte the reference's file of the same name:
# docs/architecture.md §3 promises the same bits from every variant. A refused run must write no
# image. Every failed check is listed, then the test fails.
cmake_minimum_required(VERSION 3.20)
set(failures "")
if(NOT DEFINED EXIT_CODE)
  set(EXIT_CODE 0)
endif()

file(REMOVE_RECURSE ${RUN_DIR})  # files of an earlier run must not pass the checks
set(OUT_DIR ${RUN_DIR}/out)
configure_file(${CONFIG_IN} ${RUN_DIR}/config.yaml @ONLY)
if(ISA STREQUAL "")
  set(environment --unset=TETRAY_ISA)
  set(ISA "(unset)")  # for the messages
else()
  set(environment TETRAY_ISA=${ISA})
endif()
# The launch flags of tetray_add_mpi_test (tests/CMakeLists.txt).
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env ${environment}
          ${MPIEXEC} ${NUMPROC_FLAG} 1 --oversubscribe --allow-run-as-root ${WRAPPER} ${EXE}
          ${RUN_DIR}/config.yaml
  RESULT_VARIABLE code OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(NOT code STREQUAL EXIT_CODE)
  list(APPEND failures "exit code ${code}, expected ${EXIT_CODE}")
endif()
if(NOT output MATCHES "${EXPECT}\n")
  list(APPEND failures "no line of the output ends in a match of '${EXPECT}'")
endif()

file(GLOB_RECURSE images RELATIVE ${OUT_DIR} ${OUT_DIR}/*.png ${OUT_DIR}/*.exr)
list(LENGTH images count)
if(NOT EXIT_CODE EQUAL 0)
  if(images)
    list(APPEND failures "a run that should stop wrote images: ${images}")
  endif()
elseif(NOT count EQUAL IMAGES)
  list(APPEND failures "${OUT_DIR}: ${count} images, expected ${IMAGES}")
endif()

# tetray_log.csv: at the last step, every scene's row counts hits.
if(EXIT_CODE EQUAL 0 AND EXISTS ${OUT_DIR}/tetray_log.csv)
  file(STRINGS ${OUT_DIR}/tetray_log.csv rows)
  list(POP_FRONT rows header)
  string(REPLACE "," ";" header "${header}")
  list(FIND header hits hits_column)
  list(GET rows -1 last_row)
  string(REGEX MATCH "^[0-9]+" last_step "${last_row}")
  foreach(row IN LISTS rows)
    string(REPLACE "," ";" fields "${row}")
    list(GET fields 0 step)
    list(GET fields 2 scene)
    list(GET fields ${hits_column} hits)
    if(step STREQUAL last_step AND NOT hits GREATER 0)
      list(APPEND failures "${scene} at step ${step}: no hits")
    endif()
  endforeach()
elseif(EXIT_CODE EQUAL 0)
  list(APPEND failures "${OUT_DIR}/tetray_log.csv: missing")
endif()

if(REFERENCE)
  foreach(image IN LISTS images)
    if(NOT EXISTS ${REFERENCE}/${image})
      list(APPEND failures "${image}: not in the reference run's ${REFERENCE}")
      continue()
    endif()
    file(SHA256 ${OUT_DIR}/${image} ours)
    file(SHA256 ${REFERENCE}/${image} theirs)
    if(NOT ours STREQUAL theirs)
      list(APPEND failures "${image}: differs from the reference run's")
    endif()
  endforeach()
endif()

if(failures)
  list(JOIN failures "\n  " listed)
  message(FATAL_ERROR "${CMAKE_CURRENT_LIST_FILE} (TETRAY_ISA=${ISA}):\n  ${listed}")
endif()
message(STATUS "TETRAY_ISA=${ISA}: exit code ${code}, '${EXPECT}', ${count} images")
