# Configures and builds the deal.II example (SOURCE_DIR) into BUILD_DIR against tetray installed
# in PREFIX, as its users do (docs/dealii.md):
#   cmake -DSOURCE_DIR=... -DBUILD_DIR=... -DPREFIX=... -P dealii_build.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../adaptor/run_command.cmake)

file(REMOVE_RECURSE ${BUILD_DIR})
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR} -G Ninja -DCMAKE_PREFIX_PATH=${PREFIX}
  -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${BUILD_DIR})
if(NOT EXISTS ${BUILD_DIR}/dealii_heat_insitu)
  message(FATAL_ERROR "the build left no ${BUILD_DIR}/dealii_heat_insitu")
endif()
