#!/usr/bin/env bash
# Quick start, command 2: installs what is missing, builds, and runs every test with CTest.
# Prints the build's and the tests' times (scripts/stage_time.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage_time.sh
bash scripts/install-deps.sh
stage "Release build" env BLOCKDEM_CMAKE_ARGS="-DBLOCKDEM_WERROR=ON" bash scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
stage "Release tests" ctest --test-dir build --output-on-failure -j "$jobs"
