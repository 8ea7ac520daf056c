#!/usr/bin/env bash
# The one list of Debian packages meadow needs to build, run and test.
# Used by both README commands and by .ci/run. Installs only what is missing.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git
  # Vulkan: loader, headers, lavapipe, validation layers, shader compiler and validator
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools spirv-tools
  # windowing, the walkthrough's HUD (Dear ImGui with its GLFW and Vulkan backends), math, assets, images
  libglfw3-dev libimgui-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libopenimageio-dev openimageio-tools
  # precompute: linear algebra (PCA), parallel loops
  libeigen3-dev libtbb-dev
  # precompute: ray casting for the light-transfer bake, vertex-cache optimisation of the LODs
  libembree-dev libmeshoptimizer-dev
  # tests: GoogleTest, an X server and a window manager (so minimising is real) for window tests
  libgtest-dev xvfb xauth openbox python3
  # micro-benchmarks of the precompute's hot paths (precompute/benchmarks, scripts/microbench.sh)
  libbenchmark-dev
  # robustness: clang with libFuzzer and its sanitizer runtimes (scripts/fuzz.sh)
  clang libclang-rt-14-dev
  # formatting: clang-format 14, the version .clang-format is checked with (scripts/format.sh)
  clang-format
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "meadow: installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
