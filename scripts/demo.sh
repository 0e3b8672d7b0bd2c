#!/usr/bin/env bash
# Quick start, command 1: installs what is missing, builds Release and runs the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target blockdem
out=results/demo
rm -rf "$out"
build/blockdem run scenarios/examples/column.toml --out "$out"
echo "blockdem: demo results in $out"
