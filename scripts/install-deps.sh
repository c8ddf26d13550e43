#!/usr/bin/env bash
# Installs the Debian 12 packages imucal builds and tests with. Idempotent; needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config iproute2 util-linux bc time
  libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libspdlog-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # io/: the compressed chunks of ROS 1 bags (bzip2, LZ4 frames) and MCAP files (zstd, LZ4, CRC-32 from zlib).
  libbz2-dev liblz4-dev libzstd-dev zlib1g-dev
  # io/: rosbag2's sqlite3 storage.
  libsqlite3-dev
  # LCM: C/C++ library (lcm.pc needs glib), lcm-gen, lcm.jar + lcm-spy, a JDK for the types jar,
  # and jchart2d, which lcm-spy's charts need but liblcm-java does not pull in (see scripts/lcm-spy).
  liblcm-dev liblcm-bin liblcm-java libglib2.0-dev default-jdk-headless libjchart2d-java
  # sd_notify readiness and watchdog for imucald under systemd; systemd-analyze verifies the installed units
  # (tests/install), which without it would be skipped.
  libsystemd-dev systemd
  # The real-kernel test (tests/vm): qemu boots Debian's kernel with a busybox-static initramfs.
  qemu-system-x86 busybox-static cpio xz-utils
  # The lcm-spy check: a virtual X display, a screenshot of Spy's window and OCR to read its table.
  xvfb x11-utils imagemagick tesseract-ocr tesseract-ocr-eng
  # drivers/: GPIO data-ready lines through libgpiod 1.6 (v1 API); can-utils for candump/cansend (logs to
  # replay, feeding vcan in the VM test).
  libgpiod-dev can-utils
  # tests/openvins reads the OpenVINS intrinsics file with OpenCV's cv::FileStorage, as OpenVINS does.
  libopencv-core-dev
  # ROS's own Python library reads the bags `calibrate --corrected-bag` writes (test_cli_foreign_formats).
  python3-rosbag python3-sensor-msgs
  # scripts/fuzz.sh: clang with the libFuzzer, ASan and UBSan runtimes.
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} > 0)); then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "installing: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# Debian's kernel .deb for the real-kernel test, unpacked into a cache, never installed (cached). The test
# boots an amd64 kernel with the host's binaries, so elsewhere (an arm64 board) there is nothing to fetch.
if [ "$(dpkg --print-architecture)" = amd64 ]; then
  "$(dirname "${BASH_SOURCE[0]}")/../tests/vm/fetch-kernel.sh" > /dev/null
fi
