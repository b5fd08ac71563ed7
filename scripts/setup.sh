#!/usr/bin/env bash
# Installs everything gradem needs on Debian 12 (bookworm) as root. Idempotent:
# packages already installed are left alone, and apt is not touched at all when nothing is missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libnlopt-cxx-dev libnlopt-dev libceres-dev libfccp-dev catch2
  libtomlplusplus-dev nlohmann-json3-dev libsqlite3-dev libcli11-dev
  clang
  python3-matplotlib chromium fonts-dejavu-core
  pybind11-dev python3-dev python3-numpy python3-pytest python3-scipy
  libopenmpi-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
