#!/usr/bin/env bash
# Installs every Debian package tactile-movies needs to build, run and test.
# Idempotent: packages already present are skipped by apt. Run as root on Debian 12.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build ccache clang-format pkg-config git
  # libraries
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev
  libopencv-dev libopencv-videoio-dev  # videoio: `capture VIDEO` over FFmpeg (libavcodec, libavformat)
  libavformat-dev libavcodec-dev libavutil-dev  # a live recording's frames.mkv, flushed as it goes
  libhdf5-dev
  libpng-dev libjpeg-dev  # images read with our own message handlers (capture/src/camera/image.cpp)
  libusb-1.0-0-dev libhidapi-dev
  libglfw3-dev libgl-dev libimgui-dev
  libsvm-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libcairo2-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth libgl1-mesa-dri
  xdotool  # real key presses and clicks sent to the authoring window under Xvfb
  # firmware on an emulated Cortex-M4, USB tests against fake devices, fuzzing
  gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
  umockdev libumockdev-dev
  clang libclang-rt-14-dev
  # the firmware as a USB device of a real Linux kernel: QEMU x86-64 guest (Debian kernel,
  # busybox initramfs built with cpio) and the usbredir protocol to its xHCI controller
  qemu-system-x86 linux-image-amd64 busybox-static cpio libusbredirparser-dev
  # a live session on a real V4L2 camera in that guest: the kernel's vivid driver, fed by v4l2-ctl
  v4l-utils
  # golden check of the classifiers against WEKA itself
  weka default-jre-headless
  # the Python module (`import tactile`) and its tests; matplotlib for the README's example
  python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib
  # a single-node Slurm cluster for the `cluster` tests (daemons started by the tests' helper)
  slurmctld slurmd slurm-client munge
  # live sessions: a real network stream sent by ffmpeg to the loopback address in the tests
  ffmpeg
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "setup: installing ${#missing[@]} packages: ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
