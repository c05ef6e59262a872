#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (GCC): installs what is
# missing (scripts/packages.sh), configures build-asan/ (CMake option RTBENCH_SANITIZE=ON:
# -fsanitize=address,undefined,float-cast-overflow,float-divide-by-zero -fno-sanitize-recover=all
# -fno-omit-frame-pointer, -O1 -g1: line tables, file:line in every report), builds it and runs the
# C++ tests there (see "Which tests" below). Any sanitizer report fails the
# test that triggered it; LeakSanitizer is on, with scripts/lsan.supp silencing leaks that
# belong to the Vulkan loader, Mesa (lavapipe), LLVM and TBB only (each entry says why).
#   scripts/sanitize.sh                 build + whole suite
#   scripts/sanitize.sh -R Corpus       extra arguments go to ctest (the lavapipe25 tests then do not run;
#                                       a -E of one's own replaces the one that keeps them out)
#   JOBS=N                              build and ctest parallelism (default: nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)

source scripts/packages.sh
install_missing sanitize "${rtbench_packages[@]}"

build=build-asan
jobs=${JOBS:-$(nproc)}
mkdir -p "$build"
printf '*\n' >"$build/.gitignore"  # the whole folder stays out of git
fetch_ray_query_lavapipe "$build/lavapipe-ray-query" ||
  echo "[sanitize] warning: no lavapipe 25 in $build/lavapipe-ray-query: the lavapipe25 tests will fail" >&2
cmake -S . -B "$build" -DRTBENCH_SANITIZE=ON -DRTBENCH_WITH_OIIO="${RTBENCH_WITH_OIIO:-ON}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" >"$build/configure.log" ||
  { cat "$build/configure.log" >&2; exit 1; }
echo "[sanitize] building $build/ with ASan + UBSan (log: $build/build.log)"
if ! cmake --build "$build" -j"$jobs" >"$build/build.log" 2>&1; then
  grep -E -A5 "error|Error" "$build/build.log" | head -60 >&2
  echo "[sanitize] build failed; the whole log is $build/build.log" >&2
  exit 1
fi
built=$(date +%s)
echo "[sanitize] built in $((built - start)) s; running ctest"

supp=$PWD/scripts/lsan.supp
# lavapipe stays loaded for the whole of every process (LD_PRELOAD). The Vulkan loader dlcloses the
# driver at vkDestroyInstance; LeakSanitizer finds live memory by scanning the loaded modules, so
# what lavapipe's and LLVM's globals still point to then reads as leaked, from an "<unknown
# module>" no suppression can name (seen on an AMD EPYC host, not on an Intel Xeon one: 128 bytes
# realloc'd under vkCreateInstance, in 99 tests). Kept loaded, nothing leaks. verify_asan_link_order=0:
# the preloaded driver comes before the ASan runtime in the library list (it defines no allocator).
lavapipe=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' /usr/share/vulkan/icd.d/lvp_icd.x86_64.json)
[ -f "$lavapipe" ] || { echo "[sanitize] no lavapipe driver at '$lavapipe' (mesa-vulkan-drivers)" >&2; exit 1; }
export LD_PRELOAD="$lavapipe${LD_PRELOAD:+:$LD_PRELOAD}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:verify_asan_link_order=0}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
# Which tests: SANITIZE_TESTS=all runs every test. By default two kinds are left out, each run in
# scripts/test.sh's half: the tests labelled `script` (Python and shell: charts, tables, the README
# check, the campaign and Slurm scripts; tests/CMakeLists.txt), as a sanitizer sees only the C++
# they call, which the C++ tests run; and those below, which repeat another test's C++ on an input
# only an uninstrumented library sees (Embree's code path per ISA: Golden.ReproducesAndAChangedCountFails
# and cli.check_golden run the same check here), or that repeat on every structure C++ another
# sanitized test runs: the two WavefrontRuns.*OnEveryStructure (the wavefront's host code, which
# WavefrontKernels.* run here) and EndToEnd.SimplifiedSceneIsJudgedAgainstTheFullScene (the
# simplification, which Simplify.* run here): the slowest here, 274 s of ASan test time.
select=(-LE script)
repeats='|^Golden[.]ReproducesWithEmbreeForcedToEveryIsaThisCpuRuns$|^WavefrontRuns[.].*OnEveryStructure$|^EndToEnd[.]SimplifiedSceneIsJudgedAgainstTheFullScene$'
if [ "${SANITIZE_TESTS:-}" = all ]; then
  select=()
  repeats=
fi
# The *Lavapipe25 tests load the other lavapipe (tests/CMakeLists.txt); it is the one kept loaded for
# them, in a ctest of their own. Extra arguments select among the others (ctest keeps one -R and
# one -E, so they are not given to the second run, which runs only without them).
(cd "$build" && ctest --output-on-failure -j"$jobs" --timeout 1800 --output-junit ctest-junit.xml \
  -E "^lavapipe25[.]$repeats" "${select[@]}" "$@") || status=$?
if [ $# -eq 0 ]; then
  (cd "$build" && LD_PRELOAD="$PWD/lavapipe-ray-query/libvulkan_lvp.so${LD_PRELOAD#"$lavapipe"}" \
    ctest --output-on-failure -j"$jobs" --timeout 1800 --output-junit ctest-junit-lavapipe25.xml \
    -R '^lavapipe25[.]' "${select[@]}") || status=$?
fi
/usr/bin/python3 scripts/slowest_tests.py "$build/ctest-junit.xml" || true
end=$(date +%s)
echo "[sanitize] build $((built - start)) s, tests $((end - built)) s, total $((end - start)) s"
if [ "$status" -ne 0 ]; then
  echo "[sanitize] FAILED: see the sanitizer reports above (build-asan/Testing/Temporary/LastTest.log)" >&2
fi
exit "$status"
