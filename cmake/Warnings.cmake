# Warnings are errors-in-spirit: the tree must stay at zero.
add_library(rotord_warnings INTERFACE)
target_compile_options(rotord_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual)

# The firmware configuration: every build of the core uses it, so the host tests
# exercise exactly what runs on the Cortex-M0+.
add_library(rotord_firmware_flags INTERFACE)
target_compile_options(rotord_firmware_flags INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-fno-exceptions -fno-rtti>)
