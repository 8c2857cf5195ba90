# The tree stays at zero warnings: ROTORD_WERROR (on in the default and asan
# presets, so `make test` and CI fail on a new warning) makes them errors.
option(ROTORD_WERROR "Treat compiler warnings as errors" OFF)
add_library(rotord_warnings INTERFACE)
target_compile_options(rotord_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
  $<$<BOOL:${ROTORD_WERROR}>:-Werror>)

# The firmware configuration: every build of the core uses it, so the host tests
# exercise exactly what runs on the Cortex-M0+.
add_library(rotord_firmware_flags INTERFACE)
target_compile_options(rotord_firmware_flags INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-fno-exceptions -fno-rtti>)

# A suite whose tool is missing fails with the reason instead of silently not
# being registered: scripts/install-deps.sh installs every tool.
function(rotord_missing_tool_test name reason)
  add_test(NAME ${name} COMMAND sh -c "echo \"$0\" >&2; exit 1" "${name}: ${reason}")
endfunction()
