# Cross toolchain for the Raspberry Pi Pico W's RP2040 (Cortex-M0+, ARMv6-M,
# no FPU): Debian's gcc-arm-none-eabi with newlib. The flags match what the
# pico-sdk compiles with, so sizes and code generation measured here are the
# firmware's. Used by the `embedded` preset (tests/embedded/).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

# A missing compiler must fail the configure step, not silently fall back to the
# host compiler: scripts/install-deps.sh installs it, so its absence is a bug.
find_program(ROTORD_ARM_GCC arm-none-eabi-gcc)
find_program(ROTORD_ARM_GXX arm-none-eabi-g++)
if(NOT ROTORD_ARM_GCC OR NOT ROTORD_ARM_GXX)
  message(FATAL_ERROR "arm-none-eabi-gcc/g++ not found: run scripts/install-deps.sh "
                      "(Debian packages gcc-arm-none-eabi libnewlib-arm-none-eabi "
                      "libstdc++-arm-none-eabi-newlib)")
endif()
set(CMAKE_C_COMPILER ${ROTORD_ARM_GCC})
set(CMAKE_CXX_COMPILER ${ROTORD_ARM_GXX})
set(CMAKE_ASM_COMPILER ${ROTORD_ARM_GCC})

# Bare metal has no default startup code or linker script that would link a
# test executable, so compiler checks build a static library instead.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# pico-sdk (cmake/preload/toolchains/pico_arm_cortex_m0plus_gcc.cmake): Thumb-1
# for the M0+, soft-float ABI, one section per function and object so that
# --gc-sections drops everything unreferenced.
set(ROTORD_ARM_ARCH_FLAGS "-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft")
set(CMAKE_C_FLAGS_INIT "${ROTORD_ARM_ARCH_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT "${ROTORD_ARM_ARCH_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${ROTORD_ARM_ARCH_FLAGS}")
# binutils >= 2.39 warns about the single RWX load segment every bare-metal
# image that runs from RAM has; it says nothing about our code.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections -Wl,--no-warn-rwx-segments")

# The other binutils the size report, the ISA check and the exception check use.
get_filename_component(ROTORD_ARM_BIN_DIR ${ROTORD_ARM_GCC} DIRECTORY)
find_program(ROTORD_ARM_SIZE arm-none-eabi-size HINTS ${ROTORD_ARM_BIN_DIR} REQUIRED)
find_program(ROTORD_ARM_READELF arm-none-eabi-readelf HINTS ${ROTORD_ARM_BIN_DIR} REQUIRED)
find_program(ROTORD_ARM_NM arm-none-eabi-nm HINTS ${ROTORD_ARM_BIN_DIR} REQUIRED)

# Never pick up host headers or libraries (e.g. the host's GTest package).
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
