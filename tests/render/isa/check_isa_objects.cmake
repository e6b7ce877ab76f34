# The guarantee of cmake/TetrayIsa.cmake, checked on the built objects:
# - each variant object defines exactly one global symbol, its table, so no other code can call
#   into it (or share one of its inline functions or template instantiations) except through it;
# - no baseline object (the render libraries and the adaptor without the variants) holds an AVX
#   or AVX-512 instruction;
# - the variants hold the instructions of their level: AVX-512 in avx512, AVX but no AVX-512 in
#   avx2, neither in sse4_2 (which also shows that the search below finds them);
# - no variant object runs code when the program is loaded (a static initialiser, a constructor
#   function): that would run before anything checked the CPU, and fault on one without the
#   variant's instructions.
# Arguments: NM, OBJDUMP, AR, ARCHIVES (the baseline libraries), VARIANTS (ISA=OBJECT=SYMBOL),
# WORK_DIR (scratch space for the archives' members).
cmake_minimum_required(VERSION 3.20)

# VEX and EVEX encoded instructions: a mnemonic v... on an xmm, ymm or zmm register, the upper
# halves' reset, or an AVX-512 mask register.
set(avx_pattern "^ *[0-9a-f]+:[[:space:]]+(v[a-z0-9]+[[:space:]].*%[xyz]mm|vzeroupper|.*%k[0-7])")
set(avx512_pattern "%zmm|%k[0-7]|%[xy]mm(1[6-9]|2[0-9]|3[01])")

# Sets `out` to the first lines of `object`'s disassembly that match `pattern`.
function(matching_instructions object pattern out)
  execute_process(COMMAND ${OBJDUMP} -d --no-show-raw-insn ${object}
    COMMAND grep -E -m 3 "${pattern}"
    OUTPUT_VARIABLE lines)
  set(${out} "${lines}" PARENT_SCOPE)
endfunction()

set(failures "")
set(variant_names "")
foreach(entry IN LISTS VARIANTS)
  string(REPLACE "=" ";" fields "${entry}")
  list(GET fields 0 isa)
  list(GET fields 1 object)
  list(GET fields 2 symbol)
  get_filename_component(name ${object} NAME)
  list(APPEND variant_names ${name})
  execute_process(COMMAND ${NM} -g --defined-only ${object} OUTPUT_VARIABLE symbols
    RESULT_VARIABLE nm_failed)
  string(STRIP "${symbols}" symbols)
  if(nm_failed OR NOT symbols MATCHES "^[0-9a-f]+ [DR] ${symbol}$")
    string(APPEND failures "${name}: the global symbols must be ${symbol} alone, not:\n${symbols}\n")
  endif()
  execute_process(COMMAND ${OBJDUMP} -h ${object}
    COMMAND grep -E -o "[.](init_array|preinit_array|ctors|init)([.][0-9]+)?( |$)"
    OUTPUT_VARIABLE load_time_sections)
  if(NOT load_time_sections STREQUAL "")
    string(REPLACE "\n" " " load_time_sections "${load_time_sections}")
    string(APPEND failures "${name}: code run at load time, before the CPU is checked: "
      "sections ${load_time_sections}\n")
  endif()
  matching_instructions(${object} "${avx_pattern}" avx)
  matching_instructions(${object} "${avx512_pattern}" avx512)
  if(isa STREQUAL "avx512" AND avx512 STREQUAL "")
    string(APPEND failures "${name}: no AVX-512 instruction in the avx512 variant\n")
  elseif(isa STREQUAL "avx2" AND (avx STREQUAL "" OR NOT avx512 STREQUAL ""))
    string(APPEND failures "${name}: the avx2 variant needs AVX and no AVX-512:\n${avx512}\n")
  elseif(isa STREQUAL "sse4_2" AND NOT avx STREQUAL "")
    string(APPEND failures "${name}: AVX in the sse4_2 variant:\n${avx}\n")
  endif()
endforeach()
if(variant_names STREQUAL "")
  message(FATAL_ERROR "no variants given")
endif()

set(checked 0)
file(REMOVE_RECURSE ${WORK_DIR})
foreach(archive IN LISTS ARCHIVES)
  get_filename_component(archive_name ${archive} NAME_WE)
  set(dir ${WORK_DIR}/${archive_name})
  file(MAKE_DIRECTORY ${dir})
  execute_process(COMMAND ${AR} x ${archive} WORKING_DIRECTORY ${dir} RESULT_VARIABLE ar_failed)
  if(ar_failed)
    message(FATAL_ERROR "cannot unpack ${archive}")
  endif()
  file(GLOB members ${dir}/*.o)
  foreach(member IN LISTS members)
    get_filename_component(name ${member} NAME)
    if(name IN_LIST variant_names)
      continue()
    endif()
    matching_instructions(${member} "${avx_pattern}" avx)
    if(NOT avx STREQUAL "")
      string(APPEND failures "${archive_name}(${name}): AVX outside the variants:\n${avx}\n")
    endif()
    math(EXPR checked "${checked} + 1")
  endforeach()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})

if(NOT failures STREQUAL "")
  message(FATAL_ERROR "${failures}")
endif()
list(LENGTH variant_names variant_count)
message(STATUS "${variant_count} variants, ${checked} baseline objects: no AVX outside the variants")
