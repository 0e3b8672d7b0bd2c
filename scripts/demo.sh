#!/usr/bin/env bash
# Quick start, command 1: installs what is missing, builds Release and runs the main job:
# every case of Boon, Houlsby & Utili (2015), with report and figures, into results/boon2015/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target blockdem
out=results/boon2015
rm -rf "$out"
build/blockdem reproduce boon2015 --out "$out"
echo "blockdem: report in $out/report.md"
