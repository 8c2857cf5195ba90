# Fails when a firmware image leaves less heap than newlib's malloc needs to
# start: the static RAM ends at `end`, the heap runs from there to
# __HeapLimit, and newlib's first malloc takes a whole 4 KB page from sbrk
# (number parsing allocates at boot, as does mbedtls' HMAC context). An image
# that links with less stops at its first malloc: seen with 3,936 bytes left
# (issue 29, the Pico W's shared STOP-only slot; `make hil`, goto-mag).
#
#   cmake -DNM=arm-none-eabi-nm -DELF=rotord_pico_w.elf -DMIN=4096 -P check-heap-room.cmake
cmake_minimum_required(VERSION 3.25)
foreach(var NM ELF MIN)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "usage: cmake -DNM=<nm> -DELF=<elf> -DMIN=<bytes> -P check-heap-room.cmake")
  endif()
endforeach()
execute_process(COMMAND ${NM} ${ELF} OUTPUT_VARIABLE symbols COMMAND_ERROR_IS_FATAL ANY)
if(NOT symbols MATCHES "([0-9a-fA-F]+) [A-Za-z] end\n")
  message(FATAL_ERROR "${ELF}: no end symbol (not a pico-sdk image?)")
endif()
math(EXPR end_address "0x${CMAKE_MATCH_1}")
if(NOT symbols MATCHES "([0-9a-fA-F]+) [A-Za-z] __HeapLimit\n")
  message(FATAL_ERROR "${ELF}: no __HeapLimit symbol (not a pico-sdk image?)")
endif()
math(EXPR limit_address "0x${CMAKE_MATCH_1}")
math(EXPR heap_bytes "${limit_address} - ${end_address}")
math(EXPR short_bytes "${MIN} - ${heap_bytes}")
if(heap_bytes LESS MIN)
  message(FATAL_ERROR
    "${ELF}: the static RAM leaves ${heap_bytes} bytes of heap, ${short_bytes} fewer than the "
    "${MIN} newlib's malloc takes at its first call: the firmware would stop at boot. Make the "
    "static RAM smaller (ports/pico_w/README.md, the RAM table).")
endif()
message(STATUS "${ELF}: ${heap_bytes} bytes of heap (at least ${MIN})")
