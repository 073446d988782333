#!/usr/bin/env bash
# Installs the Debian packages RRF Workbench builds and tests with.
# Idempotent: prints nothing and exits 0 when everything is already present.
# Usage: scripts/install-deps.sh [--no-gui]
set -euo pipefail

core_pkgs=(build-essential cmake pkg-config libembree-dev libtbb-dev libeigen3-dev nlohmann-json3-dev
           libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev libtinyobjloader-dev libtinyexr-dev
           libstb-dev)
gui_pkgs=(libimgui-dev libglfw3-dev python3-glad libgl-dev libgl1-mesa-dri xvfb xauth)

pkgs=("${core_pkgs[@]}")
if [[ "${1:-}" != "--no-gui" ]]; then pkgs+=("${gui_pkgs[@]}"); fi

missing=()
for p in "${pkgs[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${missing[*]}"
sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
