# Sourced by setup.sh, sanitize.sh and fuzz.sh: the Debian 12 packages rtbench needs, and
# `install_missing TAG PACKAGE...`, which installs with apt those of the packages that are not
# installed yet (idempotent: fast when all are present), naming TAG in its log line.
rtbench_packages=(
  cmake g++ make pkg-config xz-utils
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libembree-dev libtbb-dev
  libcgal-dev libcgal-demo libgmp-dev libmpfr-dev libboost-dev
  libopenimageio-dev libglm-dev libtomlplusplus-dev libcli11-dev libgtest-dev nlohmann-json3-dev libarchive-dev
  python3-matplotlib python3-pandas
)

install_missing() {  # TAG PACKAGE...
  local tag=$1 p missing=()
  shift
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "[$tag] installing: ${missing[*]}"
  local sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}
