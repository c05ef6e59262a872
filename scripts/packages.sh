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

# Lavapipe with the driver's ray tracing (Mesa 24.1 or later), for the ray-query tests only
# (tests/CMakeLists.txt names it to the Vulkan loader through VK_ICD_FILENAMES): Debian's
# <release>-backports mesa-vulkan-drivers, fetched by apt with a private source list and state
# (the archive's signature and the package's hash checked; nothing on the system changes) and
# unpacked into DEST, never installed. The archive is the one this machine's own apt sources name
# for its release (debian_archive_source below): the repository names no host and follows the
# user's mirror. Debian 12's own lavapipe (Mesa 22.3) stays the device of every other test and of
# the results. Whatever version the backports suite carries (25.0.7-2~bpo12+1 when this was
# written; DEST/package names it). Idempotent: nothing is fetched when DEST has it.
fetch_ray_query_lavapipe() {  # DEST
  local dest=$1
  if [ ! -f "$dest/libvulkan_lvp.so" ]; then
    _fetch_lavapipe_library "$dest" || return 1
  fi
  # Written every time: it names the library by its absolute path, which moves with the folder.
  printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s", "api_version": "1.3.0"}}\n' \
    "$(cd "$dest" && pwd)/libvulkan_lvp.so" >"$dest/lvp_icd.json"
}

_fetch_lavapipe_library() {  # DEST
  local dest=$1 tmp
  tmp=$(mktemp -d)
  mkdir -p "$tmp/lists/partial" "$tmp/cache/archives/partial"
  local release archive
  release=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
  if [ -z "$release" ] || ! archive=$(debian_archive_source "$release"); then
    rm -rf "$tmp"
    echo "[ray-query lavapipe] no Debian archive for '${release:-?}' with component main in this machine's apt sources (/etc/apt/sources.list, /etc/apt/sources.list.d/)" >&2
    return 1
  fi
  set -- $archive  # URI KEYRING
  echo "deb [signed-by=$2] $1 $release-backports main" >"$tmp/sources.list"
  local apt_private=(-o "Dir::Etc::SourceList=$tmp/sources.list" -o Dir::Etc::SourceParts=/nonexistent
    -o "Dir::State::Lists=$tmp/lists" -o "Dir::Cache=$tmp/cache" -o APT::Sandbox::User="$(id -un)")
  echo "[ray-query lavapipe] fetching mesa-vulkan-drivers from $release-backports ($1) into $dest"
  if ! apt-get "${apt_private[@]}" update -qq || ! (cd "$tmp" && apt-get "${apt_private[@]}" download -qq "mesa-vulkan-drivers/$release-backports"); then
    rm -rf "$tmp"
    echo "[ray-query lavapipe] could not fetch mesa-vulkan-drivers from $release-backports at $1" >&2
    return 1
  fi
  local lib
  if ! dpkg-deb -x "$tmp"/mesa-vulkan-drivers_*.deb "$tmp/root" ||
    ! lib=$(find "$tmp/root" -name libvulkan_lvp.so -print -quit) || [ -z "$lib" ]; then
    rm -rf "$tmp"
    echo "[ray-query lavapipe] the package holds no libvulkan_lvp.so" >&2
    return 1
  fi
  mkdir -p "$dest"
  cp "$lib" "$dest/libvulkan_lvp.so.part"
  mv "$dest/libvulkan_lvp.so.part" "$dest/libvulkan_lvp.so"
  basename "$tmp"/mesa-vulkan-drivers_*.deb >"$dest/package"
  rm -rf "$tmp"
}

# "URI KEYRING" of the first deb source in this machine's apt configuration that carries RELEASE
# itself (not -security or -updates) with component main: one-line sources.list entries and
# deb822 .sources stanzas alike. KEYRING is the entry's signed-by, else Debian's archive keyring.
debian_archive_source() {  # RELEASE [FILE...] (default: this machine's apt sources)
  local release=$1 files=() f
  shift
  (($#)) || set -- /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources
  for f in "$@"; do
    [ -f "$f" ] && files+=("$f")
  done
  ((${#files[@]})) || return 1
  awk -v release="$release" -v default_key=/usr/share/keyrings/debian-archive-keyring.gpg '
    function has(list, word,   n, i, a) { n = split(list, a, /[ \t]+/); for (i = 1; i <= n; i++) if (a[i] == word) return 1; return 0 }
    function emit(uri, key) { print uri, (key == "" ? default_key : key); found = 1; exit }
    function stanza_end() {
      if (types != "" && has(types, "deb") && has(suites, release) && has(comps, "main")) { split(uris, u, /[ \t]+/); emit(u[1], key) }
      types = uris = suites = comps = key = ""
    }
    FNR == 1 { stanza_end() }
    /^[ \t]*#/ { next }
    FILENAME ~ /[.]sources$/ {
      if ($0 ~ /^[ \t]*$/) { stanza_end(); next }
      field = tolower($1); sub(/:$/, "", field); value = $0; sub(/^[^:]*:[ \t]*/, "", value)
      if (field == "types") types = value; else if (field == "uris") uris = value
      else if (field == "suites") suites = value; else if (field == "components") comps = value
      else if (field == "signed-by") key = value
      next
    }
    $1 == "deb" {
      opts = ""; i = 2
      if ($2 ~ /^\[/) { while (i <= NF) { opts = opts " " $i; if ($i ~ /\]$/) break; i++ } ; i++ }
      k = ""; if (match(opts, /signed-by=[^] ]*/)) k = substr(opts, RSTART + 10, RLENGTH - 10)
      if ($(i + 1) == release) { rest = ""; for (j = i + 2; j <= NF; j++) rest = rest " " $j; if (has(rest, "main")) emit($i, k) }
    }
    END { if (!found) stanza_end(); if (!found) exit 1 }
  ' "${files[@]}"
}
