# Instruction-set variants of a library's hot kernels (TETRAY_SIMD_TARGET=dispatch,
# docs/building.md "Instruction sets"), chosen at run time by render/isa.
#
# An inline function or template instantiation (std::vector's members, std::sort, xsimd, oneTBB)
# compiled in two objects with different -march gets the same mangled name in both, and the
# linker keeps one copy: an AVX-512 copy could run on a CPU without it. So each variant's objects
# are linked into one relocatable object (ld -r, section groups resolved and dropped) whose every
# symbol but one is then made local (objcopy): the table of entry points, extern "C"
# tetrayisa_<kernels>_<isa>. Nothing outside the variant can call into it except through the
# table, and its own references to code outside it (the C++ runtime, oneTBB, other render
# functions) reach baseline code. The tests check both: tetray_isa_symbols_test and
# tetray_isa_baseline_test (tests/render/isa).

# The variants, in render/isa's kIsas order, and their x86-64 micro-architecture levels.
set(TETRAY_ISAS sse4_2 avx2 avx512)
set(TETRAY_ISA_MARCH_sse4_2 x86-64-v2)
set(TETRAY_ISA_MARCH_avx2 x86-64-v3)
set(TETRAY_ISA_MARCH_avx512 x86-64-v4)

# tetray_isa_kernels(TARGET KERNELS name SOURCES file... TABLE file REPLACED file...): adds to
# the static library TARGET one object per variant, compiled from SOURCES and TABLE (which defines
# TETRAY_ISA_TABLE(name)) with TARGET's compile options, include directories and link libraries
# and the variant's -march; REPLACED are TARGET's own sources whose functions the dispatcher now
# defines. Call it after TARGET's link libraries are set. Each variant is recorded in the global
# property TETRAY_ISA_VARIANTS as ISA=OBJECT=SYMBOL.
function(tetray_isa_kernels target)
  cmake_parse_arguments(ARG "" "KERNELS;TABLE" "SOURCES;REPLACED" ${ARGN})
  get_target_property(sources ${target} SOURCES)
  list(REMOVE_ITEM sources ${ARG_REPLACED})
  set_property(TARGET ${target} PROPERTY SOURCES ${sources})
  get_target_property(options ${target} COMPILE_OPTIONS)
  get_target_property(includes ${target} INCLUDE_DIRECTORIES)
  get_target_property(libraries ${target} LINK_LIBRARIES)
  foreach(isa IN LISTS TETRAY_ISAS)
    set(objects ${target}_${isa})
    add_library(${objects} OBJECT ${ARG_SOURCES} ${ARG_TABLE})
    target_compile_options(${objects} PRIVATE ${options} -march=${TETRAY_ISA_MARCH_${isa}}
      # Static variables of inline functions become plain weak symbols, which can be made local.
      -fno-gnu-unique)
    target_compile_definitions(${objects} PRIVATE TETRAY_ISA=${isa})
    target_include_directories(${objects} PRIVATE ${includes})
    target_link_libraries(${objects} PRIVATE ${libraries})
    set(linked ${CMAKE_CURRENT_BINARY_DIR}/${objects}_linked.o)
    set(variant ${CMAKE_CURRENT_BINARY_DIR}/${objects}.o)
    add_custom_command(OUTPUT ${variant}
      COMMAND ${CMAKE_LINKER} -r --force-group-allocation -o ${linked} $<TARGET_OBJECTS:${objects}>
      COMMAND ${CMAKE_OBJCOPY} --keep-global-symbol=tetrayisa_${ARG_KERNELS}_${isa} ${linked}
        ${variant}
      DEPENDS $<TARGET_OBJECTS:${objects}> COMMAND_EXPAND_LISTS
      COMMENT "Linking the ${isa} variant of ${target}")
    set_source_files_properties(${variant} PROPERTIES EXTERNAL_OBJECT TRUE GENERATED TRUE)
    target_sources(${target} PRIVATE ${variant})
    set_property(GLOBAL APPEND PROPERTY TETRAY_ISA_VARIANTS
      "${isa}=${variant}=tetrayisa_${ARG_KERNELS}_${isa}")
  endforeach()
endfunction()
