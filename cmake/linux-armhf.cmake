# Raspberry Pi OS 32-bit (Debian armhf, ARMv7 hard float): see debian-cross.cmake.
set(CMAKE_SYSTEM_PROCESSOR arm)
set(ROTORD_CROSS_TRIPLET arm-linux-gnueabihf)
set(ROTORD_CROSS_QEMU qemu-arm-static)
include(${CMAKE_CURRENT_LIST_DIR}/debian-cross.cmake)
