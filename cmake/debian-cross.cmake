# Cross-building the Linux daemon and its tests for a Raspberry Pi's
# architecture on an amd64 Debian: Debian's cross toolchain
# (crossbuild-essential-ARCH) and ARCH's libraries installed multiarch
# (scripts/install-deps.sh). Included by cmake/linux-arm64.cmake and
# cmake/linux-armhf.cmake, which set ROTORD_CROSS_TRIPLET and
# ROTORD_CROSS_QEMU. Tests run under qemu-user (CMAKE_CROSSCOMPILING_EMULATOR,
# so binfmt_misc is not needed) with the cross toolchain's C and C++
# libraries (-L /usr/TRIPLET: its loader; what is not there, such as
# multiarch's /usr/lib/TRIPLET libraries, qemu finds at the host's path).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_C_COMPILER ${ROTORD_CROSS_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${ROTORD_CROSS_TRIPLET}-g++)
set(CMAKE_LIBRARY_ARCHITECTURE ${ROTORD_CROSS_TRIPLET})
set(PKG_CONFIG_EXECUTABLE ${ROTORD_CROSS_TRIPLET}-pkg-config CACHE FILEPATH "pkg-config for ${ROTORD_CROSS_TRIPLET}")
find_program(ROTORD_CROSS_QEMU_PATH ${ROTORD_CROSS_QEMU})
if(NOT ROTORD_CROSS_QEMU_PATH)
  message(FATAL_ERROR "${ROTORD_CROSS_QEMU} not found: run scripts/install-deps.sh (qemu-user-static)")
endif()
set(CMAKE_CROSSCOMPILING_EMULATOR ${ROTORD_CROSS_QEMU_PATH} -L /usr/${ROTORD_CROSS_TRIPLET})
# Two architectures more to compile on a 2-core CI machine: ccache, where
# installed, keeps the second run cheap (CCACHE_DIR under build/ is the
# caller's choice).
find_program(ROTORD_CCACHE ccache)
if(ROTORD_CCACHE AND NOT DEFINED ENV{CMAKE_CXX_COMPILER_LAUNCHER})
  set(CMAKE_C_COMPILER_LAUNCHER ${ROTORD_CCACHE})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${ROTORD_CCACHE})
endif()
