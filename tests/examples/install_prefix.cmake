# Installs the build tree BUILD_DIR into PREFIX, replacing what an earlier run installed there.
#   cmake -DBUILD_DIR=... -DPREFIX=... -P install_prefix.cmake
execute_process(COMMAND ${CMAKE_COMMAND} -E rm -rf ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
  RESULT_VARIABLE failed OUTPUT_QUIET)
if(failed)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${PREFIX} failed")
endif()
