#!/usr/bin/env bash
# Fuzzes rtbench's input parsers with libFuzzer (clang 16, ASan + UBSan + float-cast-overflow +
# float-divide-by-zero): installs what is missing, configures and builds build-fuzz/ (CMake option
# RTBENCH_FUZZ=ON, CXX=clang++), then runs one target.
#   scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]
#     TARGET   fuzz_mesh (scene/mesh_io.h readMeshFile; first byte picks .off/.obj/.ply/.stl)
#              fuzz_config (harness/config.h loadExperimentText)
#              fuzz_results (a results folder's runs.csv, samples.csv, context.json; first byte picks)
#              fuzz_scene (scene/scene_description.h readSceneDescription)
#   FUZZ_KEEP_GOING=1  after a finding, start libFuzzer again (same corpus) until SECONDS are up
#   FUZZ_CLANG=N       clang version (default 16, from Debian 12's packages; Debian's default
#                      clang 14 lacks C++20 that GCC 12 has: lambdas capturing structured bindings)
#   JOBS=N             build parallelism (default 2)
# The corpus grows in build-fuzz/corpus/TARGET (out of git); seeds are rebuilt at every run in
# build-fuzz/seeds/TARGET from fuzz/seeds/TARGET and the repository's own test data; the past
# findings in tests/corpus/fuzz/TARGET/ are re-run first (which still fail); new ones go
# to build-fuzz/crashes/TARGET/. Reproduce one: build-fuzz/fuzz/TARGET FILE (RTBENCH_FUZZ_VERBOSE=1
# also prints the rtbench::Error each input gets). Exit status: 0 when
# nothing was found, else libFuzzer's.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 2 ] || usage
target=$1 seconds=$2
shift 2
case "$target" in
  mesh) target=fuzz_mesh ;;
  config) target=fuzz_config ;;
  results) target=fuzz_results ;;
  scene) target=fuzz_scene ;;
  fuzz_mesh | fuzz_config | fuzz_results | fuzz_scene) ;;
  *) echo "[fuzz] unknown target '$target' (fuzz_mesh, fuzz_config, fuzz_results, fuzz_scene)" >&2; exit 2 ;;
esac
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "[fuzz] SECONDS must be a whole number" >&2; exit 2; }

# ---- packages: what setup.sh installs (CMake configures every library) + clang and libFuzzer
source scripts/packages.sh
clang=${FUZZ_CLANG:-16}
# libclang-rt-N-dev holds libclang_rt.fuzzer*.a
install_missing fuzz "${rtbench_packages[@]}" "clang-$clang" "libclang-rt-$clang-dev" "llvm-$clang"

# ---- configure + build (only the target and the libraries it links) ----
build=build-fuzz
mkdir -p "$build"
printf '*\n' >"$build/.gitignore"  # the whole folder stays out of git
if [ -f "$build/CMakeCache.txt" ] && ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++-$clang\$" "$build/CMakeCache.txt"; then
  echo "[fuzz] $build/ was configured with another compiler: reconfiguring with clang++-$clang"
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang-$clang CXX=clang++-$clang cmake -S . -B "$build" -DRTBENCH_FUZZ=ON -DRTBENCH_TESTS=OFF -DRTBENCH_WITH_OIIO=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" >"$build/configure.log" ||
    { cat "$build/configure.log" >&2; exit 1; }
fi
echo "[fuzz] building $build/fuzz/$target (log: $build/build.log)"
if ! cmake --build "$build" --target "$target" -j"${JOBS:-2}" >"$build/build.log" 2>&1; then
  grep -E -A5 "error|Error" "$build/build.log" | head -60 >&2
  echo "[fuzz] build failed; the whole log is $build/build.log" >&2
  [ "$clang" -ge 16 ] || echo "[fuzz] clang $clang lacks some C++20 that GCC 12 has; try FUZZ_CLANG=16" >&2
  exit 1
fi

# ---- seeds: small valid (and some hostile) inputs from the repository ----
seeds=$build/seeds/$target corpus=$build/corpus/$target crashes=$build/crashes/$target
known=$build/known/$target  # tests/corpus/fuzz/TARGET: past findings, checked before fuzzing
rm -rf "$seeds" "$known"
mkdir -p "$seeds" "$corpus" "$crashes" "$known"
# fuzz_mesh inputs: first byte = the extension (byte % 4): '0' .off, '1' .obj, '2' .ply, '3' .stl
as_input() {  # FILE DEST-FOLDER
  if [ "$target" = fuzz_mesh ]; then
    local prefix
    case "${1,,}" in
      *.off) prefix=0 ;; *.obj) prefix=1 ;; *.ply) prefix=2 ;; *.stl) prefix=3 ;; *) return 0 ;;
    esac
    { printf '%s' "$prefix"; cat "$1"; } >"$2/$(basename "$1")"
  elif [ "$target" = fuzz_results ]; then  # first byte: '0' runs.csv, '1' samples.csv, '2' context.json
    local prefix
    case "$(basename "$1")" in
      runs*.csv) prefix=0 ;; samples*.csv) prefix=1 ;; context*.json) prefix=2 ;; *) return 0 ;;
    esac
    { printf '%s' "$prefix"; cat "$1"; } >"$2/$(basename "$(dirname "$1")")-$(basename "$1")"
  else
    case "$1" in *.md) return 0 ;; esac
    cp "$1" "$2/"
  fi
}
if [ "$target" = fuzz_mesh ]; then
  sources=(fuzz/seeds/fuzz_mesh/* tests/corpus/meshes/*.{off,obj,ply,stl})
  dict=fuzz/fuzz_mesh.dict
elif [ "$target" = fuzz_results ]; then
  sources=(results/golden/{runs.csv,samples.csv,context.json} results/division/{runs.csv,context.json})
  dict=fuzz/fuzz_results.dict
elif [ "$target" = fuzz_scene ]; then
  sources=(fuzz/seeds/fuzz_scene/*)
  dict=fuzz/fuzz_config.dict  # TOML's tokens; the scene's keys are in the seeds
else
  sources=(fuzz/seeds/fuzz_config/* configs/*.toml tests/harness/data/*.toml)
  dict=fuzz/fuzz_config.dict
fi
for f in "${sources[@]}"; do
  [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 65536 ] && as_input "$f" "$seeds"
done
for f in tests/corpus/fuzz/"$target"/*; do
  [ -f "$f" ] && as_input "$f" "$known"
done

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
if [ -x "/usr/lib/llvm-$clang/bin/llvm-symbolizer" ]; then
  export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-/usr/lib/llvm-$clang/bin/llvm-symbolizer}
fi
bin=$build/fuzz/$target
common=(-rss_limit_mb=1024 -timeout=10)

# ---- past findings (tests/corpus/fuzz/TARGET): which still fail? They are not seeds: a seed that
# crashes stops libFuzzer before it fuzzes.
if ls -A "$known" | grep -q .; then
  echo "[fuzz] past findings in tests/corpus/fuzz/$target/:"
  for f in "$known"/*; do
    if "$bin" "${common[@]}" "$f" >"$f.log" 2>&1; then
      echo "[fuzz]   passes now:    $(basename "$f")"
      cp "$f" "$seeds/"  # fixed: a good seed now
    else
      why=$(grep -m1 -E "^SUMMARY|FINDING|ERROR: libFuzzer" "$f.log" | cut -c1-160)
      echo "[fuzz]   still fails:   $(basename "$f"): $why"
    fi
  done
fi

# ---- run ----
flags=("${common[@]}" -dict="$dict" -artifact_prefix="$crashes/" -print_final_stats=1 -print_funcs=0)
echo "[fuzz] $target for ${seconds}s: corpus $corpus, seeds $seeds, crashes $crashes/"
marker=$build/.fuzz-start-$target
touch "$marker"
: >"$build/$target.log"
status=0
end=$((SECONDS + seconds))
set +e
while :; do
  left=$((end - SECONDS))
  [ "$left" -gt 0 ] || break
  "$bin" "${flags[@]}" -max_total_time="$left" "$@" "$corpus" "$seeds" 2>&1 | tee -a "$build/$target.log"
  rc=${PIPESTATUS[0]}
  [ "$rc" -eq 0 ] && break
  status=$rc
  # FUZZ_KEEP_GOING=1: start again (same corpus) after a finding, until the time is up
  [ "${FUZZ_KEEP_GOING:-0}" = 1 ] || break
  echo "[fuzz] finding (exit $rc); going on for $((end - SECONDS)) s more" | tee -a "$build/$target.log"
done
set -e
echo "[fuzz] log: $build/$target.log"
new=$(find "$crashes" -type f -newer "$marker" | sort)
if [ -n "$new" ]; then
  echo "[fuzz] findings of this run (crash-*, leak-*, timeout-*, oom-*, slow-unit-*):"
  sed 's/^/[fuzz]   /' <<<"$new"
  echo "[fuzz] reproduce one: RTBENCH_FUZZ_VERBOSE=1 $bin FILE"
else
  echo "[fuzz] no new findings (all findings so far: $crashes/)"
fi
exit "$status"
