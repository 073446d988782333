#!/usr/bin/env bash
# Installs the Debian packages RRF Workbench builds and tests with.
# Idempotent: prints nothing and exits 0 when everything is already present.
# Usage: scripts/install-deps.sh [--no-gui] [--sanitizers]
#   --no-gui      without the GUI's packages
#   --sanitizers  also clang with its sanitizer and libFuzzer runtimes and llvm-symbolizer, which the
#                 sanitizer and fuzz jobs need (scripts/sanitize.sh; Debian bookworm's clang 14)
set -euo pipefail

core_pkgs=(build-essential cmake ninja-build pkg-config libembree-dev libtbb-dev libeigen3-dev nlohmann-json3-dev
           libgtest-dev libgmock-dev libcli11-dev libtinyobjloader-dev libtinyexr-dev
           libstb-dev libopenmpi-dev openmpi-bin)
gui_pkgs=(libimgui-dev libglfw3-dev python3-glad libgl-dev libgl1-mesa-dri xvfb xauth)
sanitizer_pkgs=(clang-14 libclang-rt-14-dev llvm-14)

gui=1 sanitizers=0
for arg in "$@"; do
  case "$arg" in
    --no-gui) gui=0 ;;
    --sanitizers) sanitizers=1 ;;
    *) echo "usage: scripts/install-deps.sh [--no-gui] [--sanitizers]" >&2; exit 2 ;;
  esac
done
pkgs=("${core_pkgs[@]}")
if [[ $gui -eq 1 ]]; then pkgs+=("${gui_pkgs[@]}"); fi
if [[ $sanitizers -eq 1 ]]; then pkgs+=("${sanitizer_pkgs[@]}"); fi

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
