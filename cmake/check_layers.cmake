# Fails when a file of the core includes a header of a layer it may not use.
#   cmake -DCORE_DIR=core [-DLAYERS_FILE=core/layers.cmake] [-DSTAMP=file] -P check_layers.cmake
# Run by the build before any core layer compiles (core/CMakeLists.txt) and
# by the tests in tests/layers on fixture trees. Plain CMake, so it needs
# nothing the build does not already have and runs on every host that
# builds the core (Linux, the embedded preset, the pico-sdk build).
#
# Rules, each reported as "<file>:<line>: ... " with the rule broken:
#  - every directory below CORE_DIR is a layer listed in ROTORD_LAYERS;
#  - the graph names only known layers and has no cycle;
#  - a quoted #include names a file of the core ("layer/file.hpp"): the core
#    reaches into no port, simulator or test;
#  - a file includes only its own layer and the layers its layer reaches
#    through ROTORD_LAYER_<name> (transitively).
cmake_minimum_required(VERSION 3.25)

if(NOT CORE_DIR)
  message(FATAL_ERROR "check_layers.cmake: CORE_DIR not given")
endif()
get_filename_component(CORE_DIR "${CORE_DIR}" ABSOLUTE)
if(NOT LAYERS_FILE)
  set(LAYERS_FILE ${CORE_DIR}/layers.cmake)
endif()
include(${LAYERS_FILE})

set(errors 0)
# One line per broken rule, unwrapped so an editor can jump to file:line.
macro(report)
  string(CONCAT text ${ARGN})
  message(NOTICE "${text}")
  math(EXPR errors "${errors} + 1")
endmacro()

# --- the graph itself ---
foreach(layer IN LISTS ROTORD_LAYERS)
  if(NOT DEFINED ROTORD_LAYER_${layer})
    report("${LAYERS_FILE}: layer '${layer}' has no ROTORD_LAYER_${layer} (its dependencies)")
    set(ROTORD_LAYER_${layer} "")
  endif()
  foreach(dep IN LISTS ROTORD_LAYER_${layer})
    if(NOT dep IN_LIST ROTORD_LAYERS)
      report("${LAYERS_FILE}: layer '${layer}' builds on '${dep}', which is not in ROTORD_LAYERS")
    endif()
  endforeach()
endforeach()

# reach_<layer>: every layer below <layer>, found by walking the lists.
foreach(layer IN LISTS ROTORD_LAYERS)
  set(reach "")
  set(todo ${ROTORD_LAYER_${layer}})
  while(todo)
    list(POP_FRONT todo dep)
    if(dep IN_LIST reach OR NOT dep IN_LIST ROTORD_LAYERS)
      continue()
    endif()
    list(APPEND reach ${dep})
    list(APPEND todo ${ROTORD_LAYER_${dep}})
  endwhile()
  if(layer IN_LIST reach)
    report("${LAYERS_FILE}: the graph has a cycle through '${layer}'")
    list(REMOVE_ITEM reach ${layer})
  endif()
  list(SORT reach)
  set(reach_${layer} ${reach})
endforeach()

# --- every directory is a layer ---
file(GLOB entries LIST_DIRECTORIES true RELATIVE ${CORE_DIR} ${CORE_DIR}/*)
foreach(entry IN LISTS entries)
  if(IS_DIRECTORY ${CORE_DIR}/${entry} AND NOT entry IN_LIST ROTORD_LAYERS)
    report("${CORE_DIR}/${entry}/: not a layer: add it to ROTORD_LAYERS in ${LAYERS_FILE} with the layers it builds on")
  endif()
endforeach()

# Line number of the first line of `file` holding `text`, for the report.
function(line_of file text out)
  file(READ ${file} content)
  string(FIND "${content}" "${text}" at)
  string(SUBSTRING "${content}" 0 ${at} before)
  string(REGEX MATCHALL "\n" newlines "${before}")
  list(LENGTH newlines count)
  math(EXPR line "${count} + 1")
  set(${out} ${line} PARENT_SCOPE)
endfunction()

# --- every include of every file ---
set(checked 0)
foreach(layer IN LISTS ROTORD_LAYERS)
  if(NOT IS_DIRECTORY ${CORE_DIR}/${layer})
    continue()
  endif()
  file(GLOB_RECURSE sources ${CORE_DIR}/${layer}/*.cpp ${CORE_DIR}/${layer}/*.hpp
       ${CORE_DIR}/${layer}/*.h ${CORE_DIR}/${layer}/*.def)
  list(SORT sources)
  foreach(source IN LISTS sources)
    math(EXPR checked "${checked} + 1")
    file(RELATIVE_PATH shown ${CORE_DIR}/.. ${source})
    file(STRINGS ${source} includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
    foreach(directive IN LISTS includes)
      if(NOT directive MATCHES "#[ \t]*include[ \t]*([<\"])([^>\"]*)[>\"]")
        continue()
      endif()
      set(quoted FALSE)
      if(CMAKE_MATCH_1 STREQUAL "\"")
        set(quoted TRUE)
      endif()
      set(path "${CMAKE_MATCH_2}")
      set(target "")
      if(path MATCHES "^([A-Za-z0-9_]+)/")
        set(target ${CMAKE_MATCH_1})
      endif()
      if(quoted AND (NOT target IN_LIST ROTORD_LAYERS OR NOT EXISTS ${CORE_DIR}/${path}))
        line_of(${source} "${directive}" line)
        report("${shown}:${line}: includes \"${path}\", which is no file of the core: "
               "the core includes only its own headers as \"layer/file.hpp\" "
               "(and system headers with <>)")
        continue()
      endif()
      if(target STREQUAL "" OR target STREQUAL layer OR NOT target IN_LIST ROTORD_LAYERS)
        continue()  # its own layer, or a system header such as <sys/types.h>
      endif()
      if(NOT target IN_LIST reach_${layer})
        line_of(${source} "${directive}" line)
        string(REPLACE ";" " " allowed "${reach_${layer}}")
        if(allowed STREQUAL "")
          set(allowed "none")
        endif()
        report("${shown}:${line}: includes \"${path}\": layer '${layer}' may not use layer "
               "'${target}' (${layer} may include only: ${allowed}, per ${LAYERS_FILE})")
      endif()
    endforeach()
  endforeach()
endforeach()

if(errors GREATER 0)
  message(FATAL_ERROR "core layer check: ${errors} broken rule(s), listed above")
endif()
if(STAMP)
  file(WRITE ${STAMP} "${checked} files checked\n")
endif()
