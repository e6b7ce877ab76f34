# Installs the build tree into a temporary prefix, then builds and runs a solver against it from
# each language setting a user may have: C only, Fortran only (CMake projects in consumers/), C++
# against the shared library (the outside project, OUTSIDE_DIR, with tetray::tetray), and a
# Makefile with pkg-config (consumers/make). Each must render its image. Also checks what
# libtetray.so exports: the public API and nothing else.
# cmake -P with BUILD_DIR, SOURCE_DIR (tests/adaptor/consumers), OUTSIDE_DIR, WORK_DIR.
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

function(expect_image consumer_dir program)
  run(${consumer_dir}/${program} ${consumer_dir}/out)
  if(NOT EXISTS ${consumer_dir}/out/tet/tet_000000.png)
    message(FATAL_ERROR "${consumer_dir}: the consumer wrote no image")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

foreach(project c fortran)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/${project} -B ${WORK_DIR}/${project} -G Ninja
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/${project})
  expect_image(${WORK_DIR}/${project} consumer)
endforeach()
run(${CMAKE_COMMAND} -S ${OUTSIDE_DIR} -B ${WORK_DIR}/cxx_shared -G Ninja
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DTETRAY_TARGET=tetray::tetray)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/cxx_shared)
expect_image(${WORK_DIR}/cxx_shared outside_solver)

file(GLOB pc_files ${prefix}/lib*/pkgconfig/tetray.pc ${prefix}/lib/*/pkgconfig/tetray.pc)
list(GET pc_files 0 pc_file)
get_filename_component(pc_dir ${pc_file} DIRECTORY)
file(COPY ${SOURCE_DIR}/make ${SOURCE_DIR}/one_tet.c DESTINATION ${WORK_DIR}/makefile)
run(${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir} make -C ${WORK_DIR}/makefile/make consumer)
expect_image(${WORK_DIR}/makefile/make consumer)

# Every symbol libtetray.so defines is the C API or a member of the public C++ API.
file(GLOB shared_library ${prefix}/lib*/libtetray.so ${prefix}/lib/*/libtetray.so)
execute_process(COMMAND nm -D --defined-only -C ${shared_library} OUTPUT_VARIABLE symbols
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${shared_library}")
endif()
string(REPLACE "\n" ";" symbols "${symbols}")
set(public_api "^tetray_|^tetray::Adaptor::(create|create_from_yaml|execute|execute_failed|will_render|finalize|~Adaptor)\\(|^tetray::execute\\(|^tetray::vtkio::from_vtk\\(|^TETRAY_")
foreach(line IN LISTS symbols)
  string(REGEX REPLACE "^[0-9a-f]* *[A-Za-z] " "" name "${line}")
  if(name AND NOT name MATCHES "${public_api}")
    message(FATAL_ERROR "libtetray.so exports '${name}', which is not public API")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
