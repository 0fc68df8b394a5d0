# Cross-compiling syncap for arm64 (aarch64) boards with Debian's cross toolchain
# (crossbuild-essential-arm64) against an arm64 sysroot of Debian bookworm's -dev packages
# (scripts/arm64-sysroot.sh). scripts/cross-build.sh arm64 passes this file and the sysroot:
#
#   cmake -S . -B build-arm64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake \
#         -DSYNCAP_SYSROOT=/path/to/sysroot
#
# Tests run under qemu-aarch64-static with the sysroot's libraries (CMAKE_CROSSCOMPILING_EMULATOR):
# ctest runs them as it runs native ones (label "emulated", docs/guide/deploy.md).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(SYNCAP_SYSROOT "$ENV{SYNCAP_SYSROOT}" CACHE PATH "arm64 sysroot (scripts/arm64-sysroot.sh)")
if(NOT SYNCAP_SYSROOT OR NOT EXISTS "${SYNCAP_SYSROOT}/usr/lib/aarch64-linux-gnu")
  message(FATAL_ERROR "SYNCAP_SYSROOT='${SYNCAP_SYSROOT}' is not an arm64 sysroot: make one with "
                      "scripts/arm64-sysroot.sh DIR and pass -DSYNCAP_SYSROOT=DIR")
endif()
set(CMAKE_SYSROOT "${SYNCAP_SYSROOT}")
# try_compile projects read this file again: hand them the sysroot.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES SYNCAP_SYSROOT)

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# Libraries, headers and CMake packages from the sysroot only; programs (lcm-gen) from the build
# machine.
set(CMAKE_FIND_ROOT_PATH "${SYNCAP_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# pkg-config reads the sysroot's .pc files and prefixes their paths with the sysroot.
set(ENV{PKG_CONFIG_DIR} "")
set(ENV{PKG_CONFIG_LIBDIR}
    "${SYNCAP_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${SYNCAP_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${SYNCAP_SYSROOT}")

# The dynamic loader and libraries of the sysroot for every program run at build or test time.
find_program(SYNCAP_QEMU_AARCH64 NAMES qemu-aarch64-static qemu-aarch64 REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR "${SYNCAP_QEMU_AARCH64};-L;${SYNCAP_SYSROOT}")
