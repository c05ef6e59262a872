#!/usr/bin/env bash
# Install + build (the binary, the tests, the second lavapipe), then run the whole test suite
# through CTest (on lavapipe unless a GPU is present), then the 20 slowest tests and the total.
#   scripts/test.sh [CTEST ARGS...]     e.g. -R Golden, -L script, -LE script
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests
cd build
status=0
ctest --output-on-failure -j"$(nproc)" --timeout 900 --output-junit ctest-junit.xml "$@" || status=$?
/usr/bin/python3 ../scripts/slowest_tests.py ctest-junit.xml || true
exit "$status"
