#!/usr/bin/env bash
# Installs what rtbench needs from Debian 12's packages (idempotent: fast when all is present),
# then configures and builds it (CMake, Release) into build/.
#   scripts/setup.sh            install + build with OpenImageIO
#   RTBENCH_WITH_OIIO=OFF ...   build without it (as on the GPU machine)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config xz-utils
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libembree-dev libtbb-dev
  libcgal-dev libcgal-demo libgmp-dev libmpfr-dev libboost-dev
  libopenimageio-dev libglm-dev libtomlplusplus-dev libcli11-dev libgtest-dev nlohmann-json3-dev
  python3-matplotlib python3-pandas
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "[setup] installing: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRTBENCH_WITH_OIIO="${RTBENCH_WITH_OIIO:-ON}" >/dev/null
if ! cmake --build build -j"$(nproc)" >build/build.log 2>&1; then
  grep -E -A5 "error|Error" build/build.log | head -60 >&2
  echo "[setup] build failed; the whole log is build/build.log" >&2
  exit 1
fi
grep -E "warning" build/build.log | head -20 || true
echo "[setup] built build/rtbench"
