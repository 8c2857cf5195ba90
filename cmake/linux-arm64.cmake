# Raspberry Pi OS 64-bit (Debian arm64): see debian-cross.cmake.
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(ROTORD_CROSS_TRIPLET aarch64-linux-gnu)
set(ROTORD_CROSS_QEMU qemu-aarch64-static)
include(${CMAKE_CURRENT_LIST_DIR}/debian-cross.cmake)
