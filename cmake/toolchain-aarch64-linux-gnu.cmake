# Cross build for arm64 (aarch64) with Debian's cross compiler (g++-aarch64-linux-gnu) against a sysroot of
# Debian's arm64 -dev packages (scripts/arm64-test.sh makes one). Usage:
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64-linux-gnu.cmake \
#         -DIMUCAL_ARM64_SYSROOT=/var/cache/imucal-arm64-sysroot/root
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# try_compile re-reads this file in a fresh project: pass the sysroot on through the environment.
if(IMUCAL_ARM64_SYSROOT)
  set(ENV{IMUCAL_ARM64_SYSROOT} "${IMUCAL_ARM64_SYSROOT}")
elseif(DEFINED ENV{IMUCAL_ARM64_SYSROOT})
  set(IMUCAL_ARM64_SYSROOT "$ENV{IMUCAL_ARM64_SYSROOT}")
else()
  message(FATAL_ERROR "set IMUCAL_ARM64_SYSROOT to the arm64 sysroot (scripts/arm64-test.sh makes one)")
endif()
set(CMAKE_SYSROOT "${IMUCAL_ARM64_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH "${IMUCAL_ARM64_SYSROOT}")
# Libraries, headers and CMake packages from the sysroot only; programs (lcm-gen, javac, jar) from the host.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The host's lcm-gen generates the C++ headers: LCM 1.3.1's packages are not Multi-Arch, so lcm-gen:arm64
# cannot be installed beside the amd64 build's LCM, and what it generates does not depend on the target.
# Likewise lcm.jar (architecture-independent Java) for the types jar is the host's.
set(LCM_GEN_EXECUTABLE /usr/bin/lcm-gen CACHE FILEPATH "lcm-gen (the build machine's)")
set(LCM_JAR /usr/share/java/lcm.jar CACHE FILEPATH "lcm.jar (the build machine's)")

# pkg-config (lcm, libsystemd, libgpiod) reads the sysroot's .pc files and prefixes their paths with it.
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${IMUCAL_ARM64_SYSROOT}")
set(ENV{PKG_CONFIG_LIBDIR}
    "${IMUCAL_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${IMUCAL_ARM64_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_PATH} "")

# ctest and gtest_discover_tests run the arm64 binaries through qemu-user; -L makes it load the dynamic
# linker and the shared libraries from the sysroot.
find_program(IMUCAL_QEMU_AARCH64 NAMES qemu-aarch64-static qemu-aarch64 REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR "${IMUCAL_QEMU_AARCH64};-L;${IMUCAL_ARM64_SYSROOT}")
