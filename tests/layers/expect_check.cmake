# Runs cmake/check_layers.cmake on a fixture tree and checks its verdict.
#   cmake -DCHECKER=... -DCORE_DIR=... [-DLAYERS_FILE=...] [-DSOURCE_DIR=...]
#         -DEXPECT=pass|fail [-DMESSAGES=regex;regex...] -P expect_check.cmake
# EXPECT=fail also needs every regex of MESSAGES in the checker's output, so
# a test fails when the check refuses for another reason than the one meant.
cmake_minimum_required(VERSION 3.25)

set(args -DCORE_DIR=${CORE_DIR})
if(LAYERS_FILE)
  list(APPEND args -DLAYERS_FILE=${LAYERS_FILE})
endif()
if(SOURCE_DIR)
  list(APPEND args -DSOURCE_DIR=${SOURCE_DIR})
endif()
execute_process(COMMAND ${CMAKE_COMMAND} ${args} -P ${CHECKER}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(output "${out}${err}")
message("${output}")

if(EXPECT STREQUAL "pass")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "the layer check refused ${CORE_DIR}, which breaks no rule")
  endif()
elseif(EXPECT STREQUAL "fail")
  if(result EQUAL 0)
    message(FATAL_ERROR "the layer check accepted ${CORE_DIR}, which breaks a rule")
  endif()
  foreach(expected IN LISTS MESSAGES)
    if(NOT output MATCHES "${expected}")
      message(FATAL_ERROR "the layer check's report lacks: ${expected}")
    endif()
  endforeach()
else()
  message(FATAL_ERROR "EXPECT must be pass or fail, not '${EXPECT}'")
endif()
