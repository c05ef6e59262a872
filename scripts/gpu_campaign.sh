#!/usr/bin/env bash
# The GPU campaign: the configs of record on a lent GPU machine, in one remote command of at most
# 10 minutes. That machine has the NVIDIA driver but no Vulkan loader, no Embree and no package
# manager; only the repository's working tree and the ignored paths named in `carry` (64 MiB in
# all) travel to it, and at most 8 files of 16 MiB each come back from $OUT.
#
#   scripts/gpu_campaign.sh bundle          here: build build-device (no OpenImageIO, shaders
#                                           embedded), download Debian's Vulkan loader packages and
#                                           pack .gl/bundle.tar.xz: the binary, the libraries it
#                                           links that the GPU machine lacks, the cgal: meshes
#   scripts/gpu_campaign.sh run             there, from the repository root (carry [".gl"]): unpack,
#                                           list the devices, run every run of the configs as a
#                                           process of its own under RUN_CAP_S, merge each config
#                                           (a run killed or never started: a failed row saying so),
#                                           leave $OUT/campaign.tar.xz (runs.csv, samples.csv,
#                                           context.json per config) and $OUT/campaign.log
#   scripts/gpu_campaign.sh unpack TARBALL DIR
#                                           here: the results folders into DIR (e.g. results/nvidia-h200)
#                                           by `rtbench unpack` (BIN, default build/rtbench),
#                                           then `scripts/records.sh --charts DIR` draws their charts
#   scripts/gpu_campaign.sh dry-run         here, on lavapipe (CI): bundle and run with this machine's
#                                           build and libraries, MAX_RUNS runs of each config
#
# Environment (defaults in brackets):
#   CONFIGS        configs/<name>.toml to run [strategies multipass_device wavefront division control bunny structures purcell2002 christen2005 stability accuracy raytypes trees order]
#   RUN_CAP_S      seconds one run may take before its process is killed [120]
#   BUDGET_S       seconds from the start by which every run has ended: a run is capped at what is
#                  left, none starts with under 20 s left; the rest are failed rows saying so. Merging
#                  and packing come after it: keep it under the 600 s a remote command may take [420]
#   MAX_RUNS       runs of each config to run, the rest failed rows saying so (0: all) [0; dry-run 1]
#   DEVICE         Vulkan device, a name substring [NVIDIA; dry-run llvmpipe]
#   EMBREE_CONFIG  Embree's device config (its default ISA crashes on the GPU machine's AVX-512) [isa=avx2]
#   HITS           1: keep the per-ray hit records (*.hits, for `rtbench images`) in the tarball [0]
#   BIN            the binary to bundle [build-device/rtbench; dry-run build/rtbench]
# A config none of whose runs started (the budget spent before it) has no results folder: there is
# no recorded plan to write failed rows from; campaign.log names it.
set -euo pipefail
script_start=$(date +%s)
called_from=$PWD
cd "$(dirname "$0")/.."

CONFIGS=${CONFIGS:-strategies multipass_device wavefront division control bunny structures purcell2002 christen2005 stability accuracy raytypes trees order}
RUN_CAP_S=${RUN_CAP_S:-120}
BUDGET_S=${BUDGET_S:-420}
EMBREE_CONFIG=${EMBREE_CONFIG:-isa=avx2}
HITS=${HITS:-0}
bundle_limit=$((60 * 1024 * 1024))  # carry allows 64 MiB with the loader packages

# bundle BIN WITH_LIBS DIR: DIR/bundle.tar.xz from BIN, its libraries (WITH_LIBS=1) and the cgal: meshes.
bundle() {
  local bin=$1 with_libs=$2 dir=$3 stage
  stage=$(mktemp -d)
  trap 'rm -rf "$stage"' RETURN
  mkdir -p "$stage/lib" "$stage/cache" "$dir"
  cp "$bin" "$stage/rtbench"
  if [ "$with_libs" = 1 ]; then
    # Libraries the GPU machine lacks; glibc, libstdc++, libm and the Vulkan loader's own are there
    # (the loader from .gl/*.deb).
    ldd "$bin" | awk '/=> \//{print $3}' | while read -r lib; do
      case "$(basename "$lib")" in
        libc.so*|libm.so*|libstdc++.so*|libgcc_s.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libvulkan.so*) ;;
        libOpenImageIO*) echo "gpu_campaign.sh: $bin links OpenImageIO (~400 MB with its dependencies, too much to carry); build it with -DRTBENCH_WITH_OIIO=OFF" >&2; exit 3 ;;
        *) cp -L "$lib" "$stage/lib/" ;;
      esac
    done
  fi
  # The cgal: meshes, extracted from Debian's libcgal-demo here (the GPU machine has none).
  RTBENCH_CACHE="$stage/cache" "$bin" meshes > /dev/null
  XZ_OPT=-T0 tar cJf "$dir/bundle.tar.xz.tmp" -C "$stage" .
  mv "$dir/bundle.tar.xz.tmp" "$dir/bundle.tar.xz"
  local size
  size=$(find "$dir" -maxdepth 1 \( -name bundle.tar.xz -o -name '*.deb' \) -printf '%s\n' | awk '{s += $1} END {print s + 0}')
  if [ "$size" -gt "$bundle_limit" ]; then
    echo "gpu_campaign.sh: $dir holds $size bytes, over the $bundle_limit that carry can take" >&2
    return 3
  fi
  echo "gpu_campaign.sh: $dir holds $size bytes (bundle.tar.xz and the loader packages)"
}

# campaign BUNDLE_DIR OUT: every run of CONFIGS, one process each, results packed into OUT.
campaign() {
  local b=$1 out=$2 results="$1/results" log="$2/campaign.log" config n count i rc reason left cap
  local bin="$b/rtbench" start=$script_start
  mkdir -p "$results" "$out"
  export RTBENCH_CACHE="$b/cache"
  local exclude=()
  [ "$HITS" = 1 ] || exclude=(--exclude='*.hits')
  {
    echo "== $(date -u +%FT%TZ) commit $(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown), device '$DEVICE'," \
         "Embree '$EMBREE_CONFIG', run cap ${RUN_CAP_S} s, budget ${BUDGET_S} s, max runs ${MAX_RUNS:-0}"
    "$bin" devices || echo "== rtbench devices failed (exit $?): nothing can run"
  } >> "$log" 2>&1
  for config in $CONFIGS; do
    n=$("$bin" plan -o "$results" "configs/$config.toml" 2>> "$log" | sed -n 's/^\([0-9][0-9]*\) run(s).*/\1/p') || n=
    [ -n "$n" ] || { echo "== $config: rtbench plan gave no run count (see above)" >> "$log"; continue; }
    # One run per shard: run i is shard i of max(n, 2) (a plan of one run needs two shards to shard).
    count=$(( n > 1 ? n : 2 ))
    echo "== $config: $n runs" >> "$log"
    for ((i = 0; i < n; i++)); do
      if [ "${MAX_RUNS:-0}" -gt 0 ] && [ "$i" -ge "$MAX_RUNS" ]; then break; fi
      left=$(( BUDGET_S - ($(date +%s) - start) - 10 ))  # 10 s for the kill after the cap
      if [ "$left" -lt 20 ]; then
        echo "== $config: budget of ${BUDGET_S} s spent before run $i" >> "$log"
        break
      fi
      cap=$(( left < RUN_CAP_S ? left : RUN_CAP_S ))
      rc=0
      timeout -k 10 "$cap" "$bin" run -q -o "$results" -d "$DEVICE" --embree-config "$EMBREE_CONFIG" \
        --shard "$i/$count" "configs/$config.toml" >> "$log" 2>&1 || rc=$?
      # rtbench exits 1 when a run failed: its row says why. 124 or 137: killed at the cap.
      case $rc in
        0|1) ;;
        124|137) echo "== $config: run $i killed after ${cap} s" >> "$log" ;;
        *) echo "== $config: run $i: rtbench exited $rc" >> "$log" ;;
      esac
    done
    reason="killed at scripts/gpu_campaign.sh's cap of ${RUN_CAP_S} s a run (less when its budget of ${BUDGET_S} s ran short), or not started (the budget spent, or MAX_RUNS=${MAX_RUNS:-0}); campaign.log says which"
    if ! compgen -G "$results/$config/context.shard-*" > /dev/null; then
      # No run of it wrote anything: there is no recorded plan to make failed rows from.
      echo "== $config: no run started or wrote its files: no results folder" >> "$log"
    elif "$bin" merge --missing-as-failed "$reason" "$results/$config" >> "$log" 2>&1; then
      rm -f "$results/$config"/runs.shard-* "$results/$config"/samples.shard-* "$results/$config"/context.shard-* \
            "$results/$config"/.rtbench.*lock
    else
      echo "== $config: merge failed; its shard files are in the tarball as they are" >> "$log"
    fi
    echo "== $config: $(( $(date +%s) - start )) s into the campaign" >> "$log"
    # Packed after every config, so a command cut off later still brings back what is done.
    XZ_OPT=-T0 tar cJf "$out/campaign.tar.xz.tmp" "${exclude[@]}" -C "$results" . && mv "$out/campaign.tar.xz.tmp" "$out/campaign.tar.xz"
  done
  local bytes
  bytes=$(stat -c %s "$out/campaign.tar.xz" 2>/dev/null || echo 0)
  echo "== done: $(( $(date +%s) - start )) s; $bytes bytes in campaign.tar.xz" >> "$log"
  if [ "$bytes" -gt $((16 * 1024 * 1024)) ]; then
    echo "== campaign.tar.xz is over the 16 MiB a file of \$OUT may have to come back: run fewer CONFIGS (or HITS=0)" >> "$log"
  fi
}

case "${1:-}" in
  bundle)
    bin=build-device/rtbench
    [ -z "${BIN:-}" ] || bin=$(cd "$called_from" && realpath -m "$BIN")
    if [ -z "${BIN:-}" ]; then
      cmake -S . -B build-device -DCMAKE_BUILD_TYPE=Release -DRTBENCH_WITH_OIIO=OFF -DRTBENCH_TESTS=OFF > /dev/null
      cmake --build build-device -j"$(nproc)" --target rtbench
    fi
    git check-ignore -q .gl/bundle.tar.xz || { echo "gpu_campaign.sh: git must ignore .gl/ (.gitignore)" >&2; exit 2; }
    # Debian's Vulkan loader and glvnd, which the GPU machine lacks (amd64, whatever this machine is).
    lists=$(mktemp -d)
    mkdir -p "$lists/partial" .gl
    o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 "-oDir::State::Lists=$lists")
    apt-get "${o[@]}" update > /dev/null
    (cd .gl && apt-get "${o[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 > /dev/null)
    rm -rf "$lists"
    bundle "$bin" 1 .gl
    ;;
  run)
    : "${OUT:?gpu_campaign.sh run: \$OUT (the folder that comes back) is not set}"
    OUT=$(cd "$called_from" && realpath -m "$OUT")
    DEVICE=${DEVICE:-NVIDIA}
    [ -f .gl/bundle.tar.xz ] || { echo "gpu_campaign.sh run: no .gl/bundle.tar.xz (scripts/gpu_campaign.sh bundle, then carry [\".gl\"])" >&2; exit 2; }
    for f in .gl/*.deb; do [ -e "$f" ] && dpkg -x "$f" /; done
    ldconfig
    b=/tmp/rtbench-campaign
    rm -rf "$b" && mkdir -p "$b" && tar xJf .gl/bundle.tar.xz -C "$b"
    export LD_LIBRARY_PATH="$b/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
    [ -f "$icd" ] && export VK_DRIVER_FILES=$icd
    campaign "$b" "$OUT"
    tail -3 "$OUT/campaign.log"
    ;;
  unpack)
    tarball=$(cd "$called_from" && realpath -m "${2:?usage: gpu_campaign.sh unpack TARBALL DIR}")
    dir=$(cd "$called_from" && realpath -m "${3:?usage: gpu_campaign.sh unpack TARBALL DIR}")
    # The tarball comes back from a borrowed machine: plain folders and files only, capped, written
    # with our own modes (`rtbench unpack`, harness/unpack.h, says what it refuses).
    bin=build/rtbench
    [ -z "${BIN:-}" ] || bin=$(cd "$called_from" && realpath -m "$BIN")
    "$bin" unpack "$tarball" "$dir"
    ls "$dir"
    ;;
  dry-run)
    # The whole path on this machine's lavapipe: the bundle (this build, no libraries: they are
    # here), its unpacking, MAX_RUNS runs of every config, the merge and the tarball.
    DEVICE=${DEVICE:-llvmpipe}
    MAX_RUNS=${MAX_RUNS:-1}
    bin=build/rtbench
    [ -z "${BIN:-}" ] || bin=$(cd "$called_from" && realpath -m "$BIN")
    gl=$(mktemp -d)  # not .gl/, which may hold the device's bundle
    bundle "$bin" 0 "$gl"
    b=$(mktemp -d)
    OUT=$(cd "$called_from" && realpath -m "${OUT:-$(mktemp -d)}")
    tar xJf "$gl/bundle.tar.xz" -C "$b"
    script_start=$(date +%s)  # the budget counts from here: the bundling is done before a device run
    campaign "$b" "$OUT"
    rm -rf "$b" "$gl"
    echo "gpu_campaign.sh dry-run: $OUT/campaign.tar.xz and $OUT/campaign.log"
    ;;
  *)
    sed -n '2,/^set -euo/p' "$0" | sed '$d' >&2
    exit 2
    ;;
esac
