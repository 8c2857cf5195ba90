# Fails when a firmware image would reach the flash slots it keeps its data
# in: the settings (the last SETTINGS bytes of the flash) and the stored TLEs
# (the TLE bytes below them; ports/pico_w/pico_flash.hpp). A UF2 copy or
# `picotool load` writes only the sectors the image covers, so an image that
# ends below the slots leaves the settings of the previous firmware in place
# (ports/pico_w/README.md, "Firmware update"); one that reached them would
# overwrite them at the update, and the firmware's first save would overwrite
# its own code (it refuses to save then, PicoFlash::region_free).
#
#   cmake -DNM=arm-none-eabi-nm -DELF=rotord_pico_w.elf -DFLASH=2097152
#         -DSETTINGS=16384 -DTLE=16384 -P check-flash-layout.cmake
cmake_minimum_required(VERSION 3.25)
foreach(var NM ELF FLASH SETTINGS TLE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "usage: cmake -DNM=<nm> -DELF=<elf> -DFLASH=<bytes> -DSETTINGS=<bytes> "
                        "-DTLE=<bytes> -P check-flash-layout.cmake")
  endif()
endforeach()
# The wear odometer's slots below the TLEs (optional: 0 when not given).
if(NOT DEFINED ODOMETER)
  set(ODOMETER 0)
endif()
execute_process(COMMAND ${NM} ${ELF} OUTPUT_VARIABLE symbols COMMAND_ERROR_IS_FATAL ANY)
# The SDK's linker scripts mark the end of what goes into flash.
if(NOT symbols MATCHES "([0-9a-fA-F]+) [A-Za-z] __flash_binary_end\n")
  message(FATAL_ERROR "${ELF}: no __flash_binary_end symbol (not a pico-sdk image?)")
endif()
math(EXPR end_address "0x${CMAKE_MATCH_1}")
set(xip_base 268435456)  # 0x10000000, where the flash is mapped
math(EXPR image_bytes "${end_address} - ${xip_base}")
math(EXPR slots_start "${FLASH} - ${SETTINGS} - ${TLE} - ${ODOMETER}")
math(EXPR free_bytes "${slots_start} - ${image_bytes}")
math(EXPR excess_bytes "${image_bytes} - ${slots_start}")
math(EXPR slots_start_hex "${slots_start}" OUTPUT_FORMAT HEXADECIMAL)
math(EXPR image_end_hex "${image_bytes}" OUTPUT_FORMAT HEXADECIMAL)
if(image_bytes GREATER slots_start)
  message(FATAL_ERROR
    "${ELF}: the image ends at flash offset ${image_end_hex} (${image_bytes} bytes), past the "
    "start of the TLE and settings slots at ${slots_start_hex}: an update would overwrite the "
    "settings. Make the image ${excess_bytes} bytes smaller, or move the slots (pico_flash.hpp, "
    "ROTORD_*_FLASH_BYTES in ports/pico_w/CMakeLists.txt).")
endif()
message(STATUS "${ELF}: image ends at flash offset ${image_end_hex}, the TLE and settings slots "
               "start at ${slots_start_hex}: ${free_bytes} bytes to spare")
