# Installs the build tree into a temporary prefix, then configures, builds and runs the outside
# project against it (cmake -P with BUILD_DIR, SOURCE_DIR, WORK_DIR).
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

file(REMOVE_RECURSE ${WORK_DIR})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -G Ninja
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/outside_solver ${WORK_DIR}/out)
if(NOT EXISTS ${WORK_DIR}/out/tet/tet_000000.png)
  message(FATAL_ERROR "the outside solver wrote no image")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
