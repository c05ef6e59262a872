#!/usr/bin/env bash
# Install + build, then run the whole test suite through CTest (on lavapipe unless a GPU is present).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cd build && ctest --output-on-failure -j"$(nproc)" --timeout 900
