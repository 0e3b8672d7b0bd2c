#!/usr/bin/env bash
# Quick start, command 2: installs what is missing, builds, and runs every test with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
BLOCKDEM_CMAKE_ARGS="-DBLOCKDEM_WERROR=ON" bash scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j "$jobs"
