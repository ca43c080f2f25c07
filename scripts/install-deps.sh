#!/usr/bin/env bash
# Installs what this project needs on Debian 12 (as root, or through sudo).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PKGS=(
  build-essential cmake git
  libgtest-dev libcli11-dev nlohmann-json3-dev libyaml-cpp-dev libeigen3-dev
  libpugixml-dev libexpat1-dev libcairo2-dev pkgconf
  sumo sumo-tools
  python3 python3-matplotlib
  pybind11-dev python3-dev python3-pytest
  python3-pip python3-venv python3-setuptools python3-wheel
  parallel
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PKGS[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
