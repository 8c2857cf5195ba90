# Fails when a file of the core includes a header of a layer it may not use.
#   cmake -DCORE_DIR=core [-DLAYERS_FILE=core/layers.cmake] [-DSOURCE_DIR=.] [-DSTAMP=file]
#         -P check_layers.cmake
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
#    through ROTORD_LAYER_<name> (transitively);
#  - nor does it name a type of another layer by a forward declaration
#    (`class TickScheduler;`, also `namespace loop { class TickScheduler; }`
#    on one line) or an elaborated pointer (`class Foo*`): what the build
#    does not see must follow the graph too;
#  - nor a namespace that only layers out of its reach declare, by a
#    qualified name (`loop::TickScheduler`, `rotord::web::Api`): a name
#    written `X::` counts when X is a namespace some layer of the core
#    declares (`namespace rotord::web {`); the file's layer must declare X
#    itself or reach a layer that does. Comments and string literals are
#    not read;
#  - every edge is used: some file of the layer includes a header of the
#    layer the edge names;
#  - with SOURCE_DIR (the tree holding core/, sim/ and ports/), the rules of
#    the simulator and the ports (ROTORD_SIM_BUILDS_ON, ROTORD_SIM_SEAM in
#    the layers file): sim/ includes only the core layers it builds on and
#    no port; a port includes no other port, and sim/ only through the seam.
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

# The sources of each layer, and the layers that define each type name
# (`class Name {`, `struct Name :`, `enum class Name {`): a forward
# declaration elsewhere is then known to name that layer's type.
foreach(layer IN LISTS ROTORD_LAYERS)
  set(sources_${layer} "")
  set(used_${layer} "")
  if(NOT IS_DIRECTORY ${CORE_DIR}/${layer})
    continue()
  endif()
  file(GLOB_RECURSE sources ${CORE_DIR}/${layer}/*.cpp ${CORE_DIR}/${layer}/*.hpp
       ${CORE_DIR}/${layer}/*.h ${CORE_DIR}/${layer}/*.def)
  list(SORT sources)
  set(sources_${layer} ${sources})
  foreach(source IN LISTS sources)
    file(READ ${source} content)
    # Namespaces the layer declares (`namespace rotord::web {`), each part;
    # not one that only wraps a forward declaration on its line, which
    # would otherwise make another layer's namespace this one's.
    file(STRINGS ${source} openings REGEX "^[ \t]*namespace[ \t]+[A-Za-z_][A-Za-z0-9_:]*[ \t]*{")
    foreach(opening IN LISTS openings)
      if(opening MATCHES "{[ \t]*(class|struct|enum)[ \t]")
        continue()
      endif()
      string(REGEX REPLACE "^[ \t]*namespace[ \t]+([A-Za-z0-9_:]+).*" "\\1" names "${opening}")
      string(REPLACE "::" ";" names "${names}")
      foreach(name IN LISTS names)
        if(NOT layer IN_LIST namespace_of_${name})
          list(APPEND namespace_of_${name} ${layer})
        endif()
      endforeach()
    endforeach()
    string(REGEX MATCHALL "(class|struct)[ \t\r\n]+[A-Za-z_][A-Za-z0-9_]*[ \t\r\n]*(final[ \t\r\n]*)?[:{]"
           definitions "${content}")
    foreach(definition IN LISTS definitions)
      string(REGEX REPLACE "^(class|struct)[ \t\r\n]+([A-Za-z_][A-Za-z0-9_]*).*" "\\2" name
             "${definition}")
      if(NOT layer IN_LIST defined_in_${name})
        list(APPEND defined_in_${name} ${layer})
      endif()
    endforeach()
  endforeach()
endforeach()

# The verdict of the two scanners below (forward declarations, qualified
# names) on a name of `layer`'s file `source` (shown as `shown`) at the line
# holding `text`: reported unless one of the layers that own it (ARGN) is
# within the layer's reach. `named` is what the message calls it ("'Foo', a
# type"), `how` how the file names it, `advice` ends the message.
function(check_owners text named how advice)
  foreach(owner IN LISTS ARGN)
    if(owner IN_LIST reach_${layer})
      return()
    endif()
  endforeach()
  line_of(${source} "${text}" line)
  string(REPLACE ";" " " owners "${ARGN}")
  report("${shown}:${line}: names ${named} of layer '${owners}'${how}: layer '${layer}' may not "
         "use layer '${owners}' (${layer} may include only: ${allowed}, per ${LAYERS_FILE})"
         "${advice}")
  set(errors ${errors} PARENT_SCOPE)
endfunction()

# --- every include of every file ---
set(checked 0)
foreach(layer IN LISTS ROTORD_LAYERS)
  string(REPLACE ";" " " allowed "${reach_${layer}}")
  if(allowed STREQUAL "")
    set(allowed "none")
  endif()
  foreach(source IN LISTS sources_${layer})
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
      if(NOT target IN_LIST used_${layer})
        list(APPEND used_${layer} ${target})
      endif()
      if(NOT target IN_LIST reach_${layer})
        line_of(${source} "${directive}" line)
        report("${shown}:${line}: includes \"${path}\": layer '${layer}' may not use layer "
               "'${target}' (${layer} may include only: ${allowed}, per ${LAYERS_FILE})")
      endif()
    endforeach()

    # Types named without an include: `class Name;` on a line of its own or
    # after a `{` (`namespace loop { class Name; }`), not `friend class
    # Name;`; and `class Name*` / `struct Name&`.
    file(STRINGS ${source} declarations
         REGEX "((^|{)[ \t]*(class|struct)[ \t]+[A-Za-z_][A-Za-z0-9_:]*[ \t]*;)|([^A-Za-z0-9_](class|struct)[ \t]+[A-Za-z_][A-Za-z0-9_:]*[ \t]*[*&])")
    foreach(declaration IN LISTS declarations)
      if(declaration MATCHES "^[ \t]*(//|\\*|/\\*)")
        continue()  # a comment
      endif()
      string(REGEX MATCH "(class|struct)[ \t]+([A-Za-z_][A-Za-z0-9_:]*)[ \t]*[;*&]" found
             "${declaration}")
      string(REGEX REPLACE ".*::" "" name "${CMAKE_MATCH_2}")
      if(NOT DEFINED defined_in_${name} OR layer IN_LIST defined_in_${name})
        continue()  # not a type of the core (std, a template only declared), or its own
      endif()
      check_owners("${found}" "'${name}', a type" ", by a forward declaration or pointer"
                   ": invert the dependency (an interface or a callback in '${layer}') \
or add the edge" ${defined_in_${name}})
    endforeach()

    # Namespaces named by a qualified name (`web::Api`), once a file: the
    # first line that names one out of reach is reported.
    file(STRINGS ${source} qualified REGEX "[A-Za-z_][A-Za-z0-9_]*::")
    set(named_here "")
    foreach(code IN LISTS qualified)
      if(code MATCHES "^[ \t]*(//|\\*|/\\*|#)" OR code MATCHES "^[ \t]*namespace[ \t]+[A-Za-z0-9_:]+[ \t]*{")
        continue()  # a comment, a directive, or a namespace opened (see above)
      endif()
      set(line_text "${code}")
      string(REGEX REPLACE "\"([^\"\\\\]|\\\\.)*\"" "\"\"" code "${code}")
      string(REGEX REPLACE "//.*$" "" code "${code}")
      string(REGEX MATCHALL "[A-Za-z_][A-Za-z0-9_]*::" names "${code}")
      foreach(name IN LISTS names)
        string(REGEX REPLACE "::$" "" name "${name}")
        if(name IN_LIST named_here OR NOT DEFINED namespace_of_${name}
           OR layer IN_LIST namespace_of_${name})
          continue()  # seen, a class or std, or its own
        endif()
        list(APPEND named_here ${name})
        check_owners("${line_text}" "'${name}::', a namespace" "" "" ${namespace_of_${name}})
      endforeach()
    endforeach()
  endforeach()
endforeach()

# --- every edge is used ---
foreach(layer IN LISTS ROTORD_LAYERS)
  if(NOT IS_DIRECTORY ${CORE_DIR}/${layer})
    continue()
  endif()
  foreach(dep IN LISTS ROTORD_LAYER_${layer})
    if(dep IN_LIST ROTORD_LAYERS AND NOT dep IN_LIST used_${layer})
      report("${LAYERS_FILE}: layer '${layer}' builds on '${dep}', but no file of ${layer} "
             "includes a header of ${dep}: remove the edge from ROTORD_LAYER_${layer}")
    endif()
  endforeach()
endforeach()

# --- the simulator and the ports ---
# Each quoted include of a file under sim/ or ports/<port>/ whose first
# directory is a core layer, sim or ports. Other quoted includes (the
# pico-sdk's "pico/...", lwIP's "lwip/...", a port's own "daemon.hpp") are
# not the graph's business.
function(check_outside kind dir)
  file(GLOB_RECURSE outside_sources ${dir}/*.cpp ${dir}/*.hpp ${dir}/*.h ${dir}/*.c)
  list(SORT outside_sources)
  foreach(source IN LISTS outside_sources)
    file(RELATIVE_PATH shown ${SOURCE_DIR} ${source})
    file(STRINGS ${source} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(directive IN LISTS includes)
      if(NOT directive MATCHES "#[ \t]*include[ \t]*\"(([A-Za-z0-9_]+)/[^\"]*)\"")
        continue()
      endif()
      set(path "${CMAKE_MATCH_1}")
      set(target "${CMAKE_MATCH_2}")
      set(problem "")
      if(kind STREQUAL "sim")
        if(target STREQUAL "ports")
          set(problem "the simulator may not use a port")
        elseif(target IN_LIST ROTORD_LAYERS AND NOT target IN_LIST sim_reach)
          string(REPLACE ";" " " sim_allowed "${sim_reach}")
          set(problem "the simulator may use only the core layers ${sim_allowed} "
                      "(ROTORD_SIM_BUILDS_ON, per ${LAYERS_FILE})")
        endif()
      else()
        if(target STREQUAL "ports" AND NOT path MATCHES "^ports/${kind}/")
          set(problem "a port may not use another port")
        elseif(target STREQUAL "sim" AND NOT shown IN_LIST ROTORD_SIM_SEAM)
          string(REPLACE ";" " " seam "${ROTORD_SIM_SEAM}")
          if(seam STREQUAL "")
            set(seam "none")
          endif()
          set(problem "a port uses the simulator only through its seam, ${seam} "
                      "(ROTORD_SIM_SEAM, per ${LAYERS_FILE}): include that instead")
        endif()
      endif()
      if(NOT problem STREQUAL "")
        line_of(${source} "${directive}" line)
        string(CONCAT problem ${problem})
        report("${shown}:${line}: includes \"${path}\": ${problem}")
      endif()
    endforeach()
    math(EXPR outside_checked "${outside_checked} + 1")
  endforeach()
  set(outside_checked ${outside_checked} PARENT_SCOPE)
  set(errors ${errors} PARENT_SCOPE)
endfunction()

set(outside_checked 0)
if(SOURCE_DIR)
  get_filename_component(SOURCE_DIR "${SOURCE_DIR}" ABSOLUTE)
  set(sim_reach "")
  foreach(dep IN LISTS ROTORD_SIM_BUILDS_ON)
    if(NOT dep IN_LIST ROTORD_LAYERS)
      report("${LAYERS_FILE}: the simulator builds on '${dep}', which is not in ROTORD_LAYERS")
      continue()
    endif()
    list(APPEND sim_reach ${dep} ${reach_${dep}})
  endforeach()
  list(REMOVE_DUPLICATES sim_reach)
  list(SORT sim_reach)
  foreach(seam IN LISTS ROTORD_SIM_SEAM)
    if(NOT EXISTS ${SOURCE_DIR}/${seam})
      report("${LAYERS_FILE}: the simulator's seam ${seam} is not a file under ${SOURCE_DIR}")
    endif()
  endforeach()
  if(IS_DIRECTORY ${SOURCE_DIR}/sim)
    check_outside(sim ${SOURCE_DIR}/sim)
  endif()
  file(GLOB ports LIST_DIRECTORIES true RELATIVE ${SOURCE_DIR}/ports ${SOURCE_DIR}/ports/*)
  foreach(port IN LISTS ports)
    if(IS_DIRECTORY ${SOURCE_DIR}/ports/${port})
      check_outside(${port} ${SOURCE_DIR}/ports/${port})
    endif()
  endforeach()
endif()

if(errors GREATER 0)
  message(FATAL_ERROR "core layer check: ${errors} broken rule(s), listed above")
endif()
if(STAMP)
  file(WRITE ${STAMP} "${checked} files of the core and ${outside_checked} of sim/ and ports/ checked\n")
endif()
