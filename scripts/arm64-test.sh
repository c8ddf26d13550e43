#!/usr/bin/env bash
# Cross-builds imucal for arm64 (aarch64) on an amd64 Debian 12 machine and runs the arm64 unit tests under
# qemu-user. Manual, not part of CI. Usage: scripts/arm64-test.sh [gtest filter]
#
# The host's amd64 packages are never changed: only the cross compiler and qemu-user-static are installed
# (neither replaces anything). The arm64 libraries come from Debian's arm64 .debs, downloaded by a private
# apt state (its own status, lists and archive cache: the host's dpkg gets no foreign architecture) and
# unpacked with dpkg -x into a sysroot, cached outside the build tree.
#   IMUCAL_ARM64_SYSROOT  the cache (default /var/cache/imucal-arm64-sysroot): apt/ and the sysroot root/
#   IMUCAL_ARM64_BUILD    the build tree (default build-arm64/)
#   IMUCAL_ARM64_JOBS     parallel compile jobs (default nproc)
#   IMUCAL_ARM64_CXXFLAGS the build type's flags (default "-O2 -DNDEBUG": RelWithDebInfo without -g)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cache="${IMUCAL_ARM64_SYSROOT:-/var/cache/imucal-arm64-sysroot}"
build="${IMUCAL_ARM64_BUILD:-$root/build-arm64}"
jobs="${IMUCAL_ARM64_JOBS:-$(nproc)}"
sysroot="$cache/root"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

# --- host tools --------------------------------------------------------------------------------------
# The host build's own packages (cmake, lcm-gen, javac, ...) come from install-deps.sh; lcm-gen and javac
# run on the host in the cross build too.
"$root/scripts/install-deps.sh"
host_tools=(g++-aarch64-linux-gnu qemu-user-static file)
missing=()
for p in "${host_tools[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} > 0)); then
  # Refuse rather than let apt swap out a package the native build relies on.
  if $SUDO apt-get -s install --no-install-recommends "${missing[@]}" | grep -q '^Remv'; then
    echo "arm64-test: installing ${missing[*]} would remove packages; not doing it" >&2
    exit 1
  fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# --- arm64 sysroot -----------------------------------------------------------------------------------
# The -dev packages the build needs (install-deps.sh's libraries, arm64 builds of them). liblcm-dev:arm64
# is unpacked here for its headers, library and lcm.pc only: LCM 1.3.1's packages are not Multi-Arch, and
# liblcm-dev depends on liblcm-bin, so installing them for arm64 on the host would remove the amd64 ones.
# libstdc++/libc/libgcc -dev are here because the cross compiler, given a sysroot, looks for them in it.
sysroot_packages=(
  libc6-dev libstdc++-12-dev libgcc-12-dev linux-libc-dev
  libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  libgtest-dev libgmock-dev liblcm-dev libglib2.0-dev libsystemd-dev libgpiod-dev libbz2-dev liblz4-dev libzstd-dev zlib1g-dev libsqlite3-dev
)
stamp="$sysroot/.imucal-packages"
want="$(printf '%s\n' "${sysroot_packages[@]}")"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "arm64-test: building the sysroot in $sysroot"
  apt_dir="$cache/apt"
  mkdir -p "$apt_dir/lists/partial" "$apt_dir/archives/partial"
  : > "$apt_dir/status"
  # An empty status makes apt resolve the whole dependency closure; the host's sources and apt.conf.d
  # (mirror, proxy) are used as they are, so the arm64 versions match the host's amd64 ones.
  apt_opts=(-o APT::Architecture=arm64 -o APT::Architectures::=arm64
            -o Dir::State::status="$apt_dir/status" -o Dir::State::Lists="$apt_dir/lists"
            -o Dir::Cache="$apt_dir" -o Dir::Cache::archives="$apt_dir/archives"
            -o Dir::Cache::pkgcache="" -o Dir::Cache::srcpkgcache=""
            -o Debug::NoLocking=1)
  apt-get "${apt_opts[@]}" update -qq
  apt-get "${apt_opts[@]}" install -y -qq --download-only --no-install-recommends "${sysroot_packages[@]}"
  rm -rf "$sysroot"
  mkdir -p "$sysroot"
  for deb in "$apt_dir"/archives/*.deb; do
    dpkg-deb -x "$deb" "$sysroot"
  done
  # Absolute symlinks (libfoo.so -> /lib/...) would point into the host: make them relative to the sysroot.
  while IFS= read -r -d '' link; do
    target="$(readlink "$link")"
    case "$target" in
      /*) ln -sfn "$(realpath -m --relative-to="$(dirname "$link")" "$sysroot$target")" "$link" ;;
    esac
  done < <(find "$sysroot" -type l -print0)
  printf '%s\n' "$want" > "$stamp"
fi

# --- cross build -------------------------------------------------------------------------------------
# imucal_tests builds every unit test executable (one per layer, tests/CMakeLists.txt) and every program;
# benchmarks and fuzzers are left out (not unit tests). The code is optimized as the native RelWithDebInfo
# build (-O2), without its debug information: less to compile and write on a shared machine
# (IMUCAL_ARM64_CXXFLAGS="-O2 -g -DNDEBUG" to debug a fault under qemu).
start=$(date +%s)
cmake -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchain-aarch64-linux-gnu.cmake" \
  -DIMUCAL_ARM64_SYSROOT="$sysroot" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${IMUCAL_ARM64_CXXFLAGS:--O2 -DNDEBUG}" -DIMUCAL_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j"$jobs" --target imucal_tests
build_s=$(($(date +%s) - start))

qemu=(qemu-aarch64-static -L "$sysroot")
programs=()
while IFS= read -r -d '' exe; do
  if file -b "$exe" | grep -q 'ELF 64-bit LSB .*ARM aarch64'; then
    programs+=("$exe")
  else
    echo "arm64-test: $exe is not an arm64 executable: $(file -b "$exe")" >&2
    exit 1
  fi
done < <(find "$build" -path "$build/CMakeFiles" -prune -o -type f -executable -name 'imucal*' -print0)
echo "arm64-test: ${#programs[@]} arm64 executables, built in ${build_s} s"

# --- run under qemu-user -----------------------------------------------------------------------------
failed=0
for exe in "${programs[@]}"; do
  [[ "$(basename "$exe")" == imucal_*_tests ]] && continue
  if ! "${qemu[@]}" "$exe" --help >/dev/null 2>&1; then
    echo "arm64-test: $(basename "$exe") --help failed under qemu" >&2
    failed=1
  fi
done
echo "arm64-test: --help of every program under qemu: $([ $failed = 0 ] && echo ok || echo FAILED)"

# The unit tests, one qemu process per executable, less the slow suites (statistical studies, minutes
# natively) and ImucaldProcess, which starts imucald by posix_spawn and so needs a binfmt handler for aarch64. Tests
# that start imucal or imucal-sim-pub do so through qemu (tests/CMakeLists.txt); LCM traffic in the unit
# tests stays in memq://, none goes to the network.
filter="${1:--MonteCarloStudy.*:Diagnose*.*:Convergence.*:ImucaldProcess.*}"
start=$(date +%s)
cd "$build/tests"
log="$build/arm64-unit-tests.log"
set +e
# The whole output to the log (tail -f it to follow); failures and the summary on the terminal.
# The executables are those tests/CMakeLists.txt lists in unit_test_targets.cmake.
read -r -a unit_tests < <(sed -n 's/^set(imucal_unit_test_targets \(.*\))$/\1/p' unit_test_targets.cmake | tr ';' ' ')
: > "$log"
rc=0
for exe in "${unit_tests[@]}"; do
  echo "== $exe" >> "$log"
  "${qemu[@]}" "./$exe" --gtest_filter="$filter" >> "$log" 2>&1
  exe_rc=$?
  echo "arm64-test: $exe: exit $exe_rc"
  ((exe_rc == 0)) || rc=1
done
set -e
grep -E '^\[  (FAILED|PASSED|SKIPPED) ' "$log" || true
test_s=$(($(date +%s) - start))
echo "arm64-test: ${#unit_tests[@]} unit test executables --gtest_filter='$filter' under qemu: exit $rc in ${test_s} s (log: $log)"
if ((rc != 0 || failed != 0)); then exit 1; fi
