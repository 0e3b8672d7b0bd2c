#!/usr/bin/env bash
# Installs blockdem into a temporary prefix, moves the prefix, and checks that the moved
# installation works without the source tree: --version, a reproduction case (its case file and
# scripts found relative to the executable), no source path in the program, and a CMake project
# that uses the library through find_package(blockdem); the Python module imports from it.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" >/dev/null
mv "$work/prefix" "$work/moved"
bin="$work/moved/bin/blockdem"

"$bin" --version | grep -q '^blockdem [0-9]' || { echo "install_test: --version failed"; exit 1; }
# The program must not look for its data in the clone (debug and sanitizer builds do record
# source file names, so the check is on the data folders).
for data in "$source/tools" "$source/scenarios"; do
  if grep -q -a -F "$data" "$bin"; then
    echo "install_test: the installed program refers to $data in the clone"; exit 1
  fi
done
"$bin" reproduce boon2015 --case T2-1 --mode boon2012 --no-figures --quiet --out "$work/out"
test -s "$work/out/report.md" || { echo "install_test: no report.md"; exit 1; }
test -s "$work/out/T2-1/summary.json" || { echo "install_test: no summary.json"; exit 1; }

# A project of a user's: the volume of a 2 x 3 x 4 m box through the installed library (24 m^3).
cmake -S "$source/tests/install/consumer" -B "$work/consumer" \
  -DCMAKE_PREFIX_PATH="$work/moved" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/consumer" >/dev/null
volume=$("$work/consumer/consumer")
[ "$volume" = "24" ] || { echo "install_test: consumer printed '$volume', expected 24"; exit 1; }
# The Python module, when built: imported from the moved prefix by the interpreter it was built
# for, it checks a scenario file of the moved prefix (three blocks in the example column).
python_note=""
if [ -d "$work/moved/lib/python3/dist-packages/blockdem" ]; then
  python=$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  blocks=$(cd "$work" && PYTHONPATH="$work/moved/lib/python3/dist-packages" "$python" -c "
import blockdem, sys
assert blockdem.__file__.startswith('$work/moved/'), blockdem.__file__
print(len(blockdem.load('$work/moved/share/blockdem/scenarios/examples/column.toml').block_names))")
  [ "$blocks" = "4" ] || { echo "install_test: python import printed '$blocks', expected 4"; exit 1; }
  python_note=", the Python module imports from the moved prefix"
fi
echo "install_test: installed, moved, reproduced T2-1, find_package(blockdem) works$python_note"
