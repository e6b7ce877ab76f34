# Installs the build tree into WORK_DIR, then runs the plane test against the installed package
# with the system Python in a bare environment: nothing on PYTHONPATH but the install's package
# folder and the tests' own helpers, no LD_LIBRARY_PATH (the module finds libtetray.so through
# its RUNPATH).
#   cmake -DBUILD_DIR=... -DWORK_DIR=... -DPACKAGE_DIR=<relative to the prefix> -DPYTHON=...
#         -DTEST_DIR=... -P install_test.cmake
set(PREFIX ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/../examples/install_prefix.cmake)
set(site ${WORK_DIR}/${PACKAGE_DIR})
set(bare env -i PATH=/usr/bin:/bin HOME=${WORK_DIR} PYTHONPATH=${site}:${TEST_DIR}
  PYTHONDONTWRITEBYTECODE=1)
execute_process(COMMAND ${bare} ${PYTHON} -c
  "import tetray; assert tetray.__file__.startswith('${site}/'), tetray.__file__"
  RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "tetray does not import from ${site}")
endif()
execute_process(COMMAND ${bare} ${PYTHON} ${TEST_DIR}/test_adaptor.py
  AdaptorTest.test_plane_where_the_camera_sees_it RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "the plane test failed against the installed package")
endif()
