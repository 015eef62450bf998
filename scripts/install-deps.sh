#!/usr/bin/env bash
# Installs, with apt, only the Debian 12 packages that are missing. Safe to run again.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools glslang-dev spirv-tools libspirv-cross-c-shared-dev
  libglm-dev libtinygltf-dev libopenexr-dev libstb-dev zlib1g-dev
  libfreetype-dev libfontconfig-dev fonts-dejavu-core  # captions on comparison strips
  nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev
  python3-matplotlib assimp-testmodels
  libembree-dev  # the CPU anchor of the bvh benchmark (optional: bench/CMakeLists.txt)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
