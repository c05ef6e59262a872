#!/usr/bin/env bash
# Installs what rtbench needs from Debian 12's packages (idempotent: fast when all is present),
# then configures and builds the rtbench binary (CMake, Release) into build/.
#   scripts/setup.sh            install + build build/rtbench, with OpenImageIO
#   scripts/setup.sh --tests    also the test binary and the second lavapipe the tests use
#   RTBENCH_WITH_OIIO=OFF ...   build without it (as on the GPU machine)
set -euo pipefail
cd "$(dirname "$0")/.."
tests=0
[ "${1:-}" = "--tests" ] && tests=1

source scripts/packages.sh
install_missing setup "${rtbench_packages[@]}"

if ((tests)); then
  # The second lavapipe of the *Lavapipe25 tests (not of any result): without it those tests fail.
  fetch_ray_query_lavapipe build/lavapipe-ray-query ||
    echo "[setup] warning: no lavapipe 25 in build/lavapipe-ray-query: the *Lavapipe25 tests will fail" >&2
fi

mkdir -p build
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRTBENCH_WITH_OIIO="${RTBENCH_WITH_OIIO:-ON}" >/dev/null
targets=(--target rtbench)
((tests)) && targets=()
if ! cmake --build build "${targets[@]}" -j"$(nproc)" >build/build.log 2>&1; then
  grep -E -A5 "error|Error" build/build.log | head -60 >&2
  echo "[setup] build failed; the whole log is build/build.log" >&2
  exit 1
fi
grep -E "warning" build/build.log | head -20 || true
echo "[setup] built build/rtbench$(((tests)) && echo ' and the tests')"
