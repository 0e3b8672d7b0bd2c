#!/usr/bin/env bash
# Installs the Debian packages blockdem needs to build, test and draw figures (Debian 12).
# Does nothing when they are all present; otherwise runs apt-get (as root, or through sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format libgomp1 clang libomp-dev
  libeigen3-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev coinor-libclp-dev
  libopenmpi-dev openmpi-bin
  python3 python3-numpy python3-matplotlib python3-dev pybind11-dev python3-pybind11
  python3-pytest python3-vtk9
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "blockdem: installing missing Debian packages: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "blockdem: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
