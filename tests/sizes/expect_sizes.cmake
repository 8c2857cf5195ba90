# Runs scripts/check-sizes.py on directories and checks its verdict.
#   cmake -DCHECKER=... -DROOT=... -DDIRS=dir;dir -DEXPECT=pass|fail
#         [-DMESSAGES=regex;regex...] -P expect_sizes.cmake
# Every regex of MESSAGES must be in the check's output, for pass (what it
# measured) and fail (so a test fails when the check refuses for another
# reason than the one meant).
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/expect_verdict.cmake)

find_program(PYTHON3 python3 REQUIRED)
string(REPLACE ";" " " subject "${DIRS}")
rotord_expect_verdict(CHECK "the size check" SUBJECT "${subject}" EXPECT ${EXPECT}
                      COMMAND ${PYTHON3} ${CHECKER} --max-file-lines 400 --max-function-lines 60
                              --root ${ROOT} ${DIRS}
                      MESSAGES ${MESSAGES})
