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

# tetray_render_stage(NAME): the library tetray_render_NAME of render/NAME/, with the compile
# options every render kernel needs.
function(tetray_render_stage name)
  tetray_folder_library(tetray_render_${name})
  get_target_property(type tetray_render_${name} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    return()
  endif()
  # The watertight edge tests rely on exact antisymmetry of products (a*b - c*d == -(c*d - a*b));
  # fused multiply-add contraction would break it.
  target_compile_options(tetray_render_${name} PRIVATE -ffp-contract=off)
  # The renderer never reads errno; without it the compiler may vectorize sqrt (packet set-up).
  # The results are the same IEEE operations either way.
  target_compile_options(tetray_render_${name} PRIVATE -fno-math-errno)
  # GCC 12's AVX-512 headers initialise _mm512_undefined_ps() from itself, which
  # -Wmaybe-uninitialized reports at every inlined min/max (a known false positive).
  # At -O1/-O2 with the sanitizers GCC reports the same spot as -Wuninitialized.
  # (GCC's option: clang, which builds the fuzz targets, has no such warning and would warn of
  # an unknown option instead.)
  target_compile_options(tetray_render_${name} PRIVATE
    $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>
    $<$<BOOL:${TETRAY_SANITIZE}>:-Wno-uninitialized>)
endfunction()
