#!/usr/bin/env bash
# Quick start: install + build, then run the default experiment (configs/bunny.toml).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build/rtbench run "${1:-configs/bunny.toml}"
