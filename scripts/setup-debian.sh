#!/usr/bin/env bash
# Installs every Debian 12 package Obscura builds, tests and demos with.
# Idempotent: packages already installed are skipped, and apt is not touched
# at all when nothing is missing (so repeated runs cost a dpkg query only).
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config git
  # GL through Mesa: EGL surfaceless + llvmpipe, GLVND front ends
  libegl-dev libgl-dev libopengl-dev libgl1-mesa-dri libegl-mesa0 libglx-mesa0
  # glad2 generator (run as /usr/bin/glad --reproducible)
  python3-glad
  # libraries
  libglm-dev libopenimageio-dev openimageio-tools libassimp-dev nlohmann-json3-dev libcli11-dev
  libglfw3-dev libimgui-dev
  # tests and shader validation
  catch2 glslang-tools xvfb xauth binutils
  # ground truth and reports
  libembree-dev python3-matplotlib python3-numpy
  # real test content (never copied into the repository)
  assimp-testmodels blender-data
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup-debian: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup-debian: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
