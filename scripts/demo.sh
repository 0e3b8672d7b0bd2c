#!/usr/bin/env bash
# Quick start, command 1: installs what is missing, builds Release (the program and the Python
# module) and runs the main job:
# every case of Boon, Houlsby & Utili (2015), with report and figures, into results/boon2015/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target blockdem
# The Python module too when it is configured, so that `cmake --install build` finds everything it
# installs.
# (grep reads the whole list: with -q it could stop early and fail the pipe under pipefail)
if cmake --build build --target help | grep -w blockdem_python >/dev/null; then
  cmake --build build -j "$(nproc 2>/dev/null || echo 2)" --target blockdem_python
fi
out=results/boon2015
rm -rf "$out"
build/blockdem reproduce boon2015 --out "$out"
echo "blockdem: report in $out/report.md"
