# Fails unless every image holds only ARMv6-M (Thumb-1) code.
# qemu's mps2-an385 has a Cortex-M3 (ARMv7-M): it would silently execute a
# Thumb-2 instruction that faults on the RP2040's Cortex-M0+, e.g. from a
# library built for the wrong multilib. The linker merges the build attributes
# of every object it links, so the image's attributes show the highest
# architecture that went in.
#   cmake -DREADELF=arm-none-eabi-readelf -DIMAGES="a|b" -P check-isa.cmake
cmake_minimum_required(VERSION 3.25)
string(REPLACE "|" ";" images "${IMAGES}")
set(failed FALSE)
foreach(image IN LISTS images)
  execute_process(COMMAND ${READELF} -A ${image} OUTPUT_VARIABLE attributes
                  COMMAND_ERROR_IS_FATAL ANY)
  string(REGEX MATCH "Tag_CPU_arch: [^\n]*" arch "${attributes}")
  string(REGEX MATCH "Tag_THUMB_ISA_use: [^\n]*" thumb "${attributes}")
  string(REGEX MATCH "Tag_ARM_ISA_use: [^\n]*" arm "${attributes}")
  message(STATUS "${image}: ${arch}, ${thumb}, ${arm}")
  # An absent Tag_ARM_ISA_use means no ARM (A32) code.
  if(NOT arch STREQUAL "Tag_CPU_arch: v6S-M" OR NOT thumb STREQUAL "Tag_THUMB_ISA_use: Thumb-1"
     OR NOT (arm STREQUAL "" OR arm STREQUAL "Tag_ARM_ISA_use: No"))
    message(SEND_ERROR "${image} is not pure ARMv6-M Thumb-1 code")
    set(failed TRUE)
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "ISA check failed")
endif()
