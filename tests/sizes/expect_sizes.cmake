# Runs scripts/check-sizes.py on directories and checks its verdict.
#   cmake -DCHECKER=... -DROOT=... -DDIRS=dir;dir -DEXPECT=pass|fail
#         [-DMESSAGES=regex;regex...] -P expect_sizes.cmake
# Every regex of MESSAGES must be in the check's output, for pass (what it
# measured) and fail (so a test fails when the check refuses for another
# reason than the one meant).
cmake_minimum_required(VERSION 3.25)

find_program(PYTHON3 python3 REQUIRED)
execute_process(COMMAND ${PYTHON3} ${CHECKER} --max-file-lines 400 --max-function-lines 60
                        --root ${ROOT} ${DIRS}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(output "${out}${err}")
message("${output}")

if(EXPECT STREQUAL "pass")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "the size check refused ${DIRS} (exit ${result})")
  endif()
elseif(EXPECT STREQUAL "fail")
  if(result EQUAL 0)
    message(FATAL_ERROR "the size check accepted ${DIRS}, which is over a limit")
  endif()
else()
  message(FATAL_ERROR "EXPECT must be pass or fail, not '${EXPECT}'")
endif()
foreach(expected IN LISTS MESSAGES)
  if(NOT output MATCHES "${expected}")
    message(FATAL_ERROR "the size check's report lacks: ${expected}")
  endif()
endforeach()
