# Runs cmake/check_layers.cmake on a fixture tree and checks its verdict.
#   cmake -DCHECKER=... -DCORE_DIR=... [-DLAYERS_FILE=...] [-DSOURCE_DIR=...]
#         -DEXPECT=pass|fail [-DMESSAGES=regex;regex...] -P expect_check.cmake
# EXPECT=fail also needs every regex of MESSAGES in the checker's output, so
# a test fails when the check refuses for another reason than the one meant.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/expect_verdict.cmake)

set(args -DCORE_DIR=${CORE_DIR})
if(LAYERS_FILE)
  list(APPEND args -DLAYERS_FILE=${LAYERS_FILE})
endif()
if(SOURCE_DIR)
  list(APPEND args -DSOURCE_DIR=${SOURCE_DIR})
endif()
rotord_expect_verdict(CHECK "the layer check" SUBJECT ${CORE_DIR} EXPECT ${EXPECT}
                      COMMAND ${CMAKE_COMMAND} ${args} -P ${CHECKER} MESSAGES ${MESSAGES})
