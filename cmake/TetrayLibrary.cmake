# tetray_library(NAME DIR [INTERFACE]): a library whose include root holds only its own folder.
# The root is a directory in the build tree with one symbolic link, <prefix>/<folder> ->
# the source folder, so `#include "render/trace/trace.hpp"` resolves only in targets that link
# the trace library: a header of a stage a target does not depend on is a build error.
function(tetray_include_root target folder)
  set(root ${PROJECT_BINARY_DIR}/include_roots/${target})
  get_filename_component(parent ${root}/${folder} DIRECTORY)
  file(MAKE_DIRECTORY ${parent})
  if(NOT EXISTS ${root}/${folder})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${root}/${folder} SYMBOLIC)
  endif()
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE $<BUILD_INTERFACE:${root}>)
  else()
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${root}>)
  endif()
endfunction()

# A static library of the .cpp files in the current source folder, with that folder as its
# include root (see tetray_include_root), compiled with the project's warnings.
function(tetray_folder_library target)
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(sources)
    add_library(${target} STATIC ${sources})
    target_link_libraries(${target} PRIVATE tetray_warnings)
  else()
    add_library(${target} INTERFACE)
  endif()
  tetray_include_root(${target} ${folder})
endfunction()
