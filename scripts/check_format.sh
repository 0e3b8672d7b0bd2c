#!/usr/bin/env bash
# Checks that every tracked C++ file is formatted with the repository's .clang-format
# (clang-format from Debian 12, version 14). Lists the files that differ; exit 1 if any.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check_format: clang-format is not installed (scripts/install-deps.sh installs it)" >&2; exit 1; }
bad=()
while IFS= read -r f; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(git ls-files '*.cpp' '*.hpp')
if [ ${#bad[@]} -gt 0 ]; then
  printf 'check_format: not formatted (run clang-format -i): %s\n' "${bad[@]}"
  exit 1
fi
echo "check_format: every C++ file formatted"
