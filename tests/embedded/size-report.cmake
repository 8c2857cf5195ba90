# Prints the core's flash and static RAM on the Cortex-M0+ and fails when one
# exceeds its budget in budgets.txt.
#   flash = text + data (code, constants, initial values of variables)
#   RAM   = data + bss  (static variables; stacks and heap not included)
# Two views:
#   core_library_*  every object of the core's layer libraries (librotord_<layer>.a,
#                   core/layers.cmake), summed, before --gc-sections: an upper
#                   bound that needs no knowledge of the core's API;
#   firmware_core_* size_probe.cpp linked with the core minus the same image
#                   without it: what the core, with the newlib/libgcc code it
#                   pulls in (soft float, formatting), adds to a firmware.
#   cmake -DSIZE=... "-DCORE_LIBRARIES=a.a;b.a" -DPROBE=... -DBASELINE=... -DBUDGETS=... -P size-report.cmake
cmake_minimum_required(VERSION 3.25)

# Returns "text;data;bss" of one line of `size -B` output.
function(parse_berkeley line out)
  string(REGEX MATCH "^[ \t]*([0-9]+)[ \t]+([0-9]+)[ \t]+([0-9]+)" matched "${line}")
  if(NOT matched)
    message(FATAL_ERROR "cannot parse size output: ${line}")
  endif()
  set(${out} "${CMAKE_MATCH_1};${CMAKE_MATCH_2};${CMAKE_MATCH_3}" PARENT_SCOPE)
endfunction()

function(elf_size image out)
  execute_process(COMMAND ${SIZE} -B ${image} OUTPUT_VARIABLE text COMMAND_ERROR_IS_FATAL ANY)
  string(REPLACE "\n" ";" lines "${text}")
  list(GET lines 1 line)  # after the header
  parse_berkeley("${line}" numbers)
  set(${out} "${numbers}" PARENT_SCOPE)
endfunction()

if(NOT CORE_LIBRARIES)
  message(FATAL_ERROR "size-report.cmake: CORE_LIBRARIES (the core's layer libraries) not given")
endif()
# -t: one TOTALS line over every object of every library given.
execute_process(COMMAND ${SIZE} -B -t ${CORE_LIBRARIES} OUTPUT_VARIABLE text
                COMMAND_ERROR_IS_FATAL ANY)
string(REGEX MATCH "[^\n]*\\(TOTALS\\)" totals "${text}")
parse_berkeley("${totals}" library)
elf_size(${PROBE} probe)
elf_size(${BASELINE} baseline)

list(GET library 0 lib_text)
list(GET library 1 lib_data)
list(GET library 2 lib_bss)
list(GET probe 0 probe_text)
list(GET probe 1 probe_data)
list(GET probe 2 probe_bss)
list(GET baseline 0 base_text)
list(GET baseline 1 base_data)
list(GET baseline 2 base_bss)

math(EXPR core_library_flash "${lib_text} + ${lib_data}")
math(EXPR core_library_ram "${lib_data} + ${lib_bss}")
math(EXPR firmware_core_flash "${probe_text} + ${probe_data} - ${base_text} - ${base_data}")
math(EXPR firmware_core_ram "${probe_data} + ${probe_bss} - ${base_data} - ${base_bss}")
math(EXPR probe_flash "${probe_text} + ${probe_data}")
math(EXPR probe_ram "${probe_data} + ${probe_bss}")

# Right-aligns numbers for the table below.
function(pad value out)
  string(LENGTH "${value}" length)
  math(EXPR spaces "8 - ${length}")
  string(REPEAT " " ${spaces} padding)
  set(${out} "${padding}${value}" PARENT_SCOPE)
endfunction()

function(row label text data bss)
  pad(${text} text)
  pad(${data} data)
  pad(${bss} bss)
  message("  ${label}${text}${data}${bss}")
endfunction()

message("Core on Cortex-M0+, bytes            text    data     bss")
row("core libraries, all objects   " ${lib_text} ${lib_data} ${lib_bss})
row("firmware-like image           " ${probe_text} ${probe_data} ${probe_bss})
row("same image without the core   " ${base_text} ${base_data} ${base_bss})

# budgets.txt: "name bytes" per line; '#' starts a comment.
file(STRINGS ${BUDGETS} lines)
set(failed FALSE)
set(checked 0)
foreach(line IN LISTS lines)
  string(REGEX REPLACE "#.*" "" line "${line}")
  string(STRIP "${line}" line)
  if(line STREQUAL "")
    continue()
  endif()
  if(NOT line MATCHES "^([a-z_]+)[ \t]+([1-9][0-9]*)$")
    message(FATAL_ERROR "${BUDGETS}: cannot parse '${line}'")
  endif()
  set(name ${CMAKE_MATCH_1})
  set(budget ${CMAKE_MATCH_2})
  if(NOT DEFINED ${name})
    message(FATAL_ERROR "${BUDGETS}: unknown measure '${name}'")
  endif()
  math(EXPR percent "100 * ${${name}} / ${budget}")
  if(${name} GREATER budget)
    message(SEND_ERROR "OVER BUDGET: ${name} = ${${name}} > ${budget}")
    set(failed TRUE)
  else()
    message("  ${name} = ${${name}} of ${budget} (${percent}%)")
  endif()
  math(EXPR checked "${checked} + 1")
endforeach()
if(checked EQUAL 0)
  message(FATAL_ERROR "${BUDGETS}: no budgets")
endif()
if(failed)
  message(FATAL_ERROR "size budget exceeded; see tests/embedded/README.md")
endif()
