#!/usr/bin/env bash
# Installs the Debian packages relume builds and runs with. Idempotent: packages already present
# are skipped, and apt-get runs only when something is missing. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers clinfo
  libglpk-dev libzstd-dev libopenjp2-7-dev zlib1g-dev libopenimageio-dev openimageio-tools libeigen3-dev
  libgtest-dev libgmock-dev libcli11-dev nlohmann-json3-dev python3-numpy python3-openimageio
  pybind11-dev python3-dev python3-pytest python3-matplotlib
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev ffmpeg
  clang libclang-rt-14-dev locales-all
  libcpp-httplib-dev chromium chromium-driver python3-selenium esbuild
  libopenmpi-dev openmpi-bin
)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install_deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
