# What the tests of a source check have in common (tests/layers: the layer
# check; tests/sizes: the size check): run the check on a tree, show its
# report, and compare its verdict with the one expected.
#
# rotord_expect_verdict(CHECK <name> SUBJECT <what it checked> EXPECT pass|fail
#                       COMMAND <command...> [MESSAGES <regex>...])
# EXPECT pass: the check exits 0; fail: it does not. Every regex of
# MESSAGES must be in its output either way (what it measured, or why it
# refused: a test fails when the check refuses for another reason than the
# one meant).
function(rotord_expect_verdict)
  cmake_parse_arguments(arg "" "CHECK;SUBJECT;EXPECT" "COMMAND;MESSAGES" ${ARGN})
  execute_process(COMMAND ${arg_COMMAND} RESULT_VARIABLE result OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  set(output "${out}${err}")
  message("${output}")
  if(arg_EXPECT STREQUAL "pass")
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "${arg_CHECK} refused ${arg_SUBJECT}, which breaks no rule (exit ${result})")
    endif()
  elseif(arg_EXPECT STREQUAL "fail")
    if(result EQUAL 0)
      message(FATAL_ERROR "${arg_CHECK} accepted ${arg_SUBJECT}, which breaks a rule")
    endif()
  else()
    message(FATAL_ERROR "EXPECT must be pass or fail, not '${arg_EXPECT}'")
  endif()
  foreach(expected IN LISTS arg_MESSAGES)
    if(NOT output MATCHES "${expected}")
      message(FATAL_ERROR "${arg_CHECK}'s report lacks: ${expected}")
    endif()
  endforeach()
endfunction()
