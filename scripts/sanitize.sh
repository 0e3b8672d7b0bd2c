#!/usr/bin/env bash
# Builds the tests with AddressSanitizer and UndefinedBehaviorSanitizer in build-sanitize/ and
# runs every test there: any memory error, leak or undefined behaviour fails the run. Prints the
# build's and the tests' times (scripts/stage_time.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage_time.sh
bash scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Tests whose length serves only their timing or breadth run shorter (tests/support/sanitized_run.hpp).
export BLOCKDEM_TEST_SANITIZED=1
# The Python module is off here: a sanitized extension cannot load into an unsanitized python3.
# Without MPI: Open MPI keeps allocations to process exit that LeakSanitizer would report; the
# MPI tests skip there and run in the ordinary build.
# -O1 and line tables only: the sanitizers check the same at -O1, their reports still name file
# and line, and the build takes far less time than at -O2 with full debug information.
# The test program's own files at -O0 (the library kept at -O1) were tried on 30 November 2026:
# they compiled in 342 s of CPU against 799 s, but the tests that drive the library's inline
# kernels and Eigen from their own code ran 10 to 20 times slower (FaceFullSlip's oracle test
# under a varying stress 14 s against 236 s), which costs more than the build saves.
# Without the instrumentation for returned stack frames: its check is off unless ASAN_OPTIONS
# sets detect_stack_use_after_return=1 (off by default, and not set here), so it checked nothing;
# without it two of the largest files compiled in 36 s instead of 39 and 41 s (30 November 2026).
# Clang with LLVM's OpenMP runtime, as scripts/sanitize_thread.sh (GCC until 29 November 2026):
# on the 2-core machine, the same day, the 293 tests both runs finished took 1357 s of test time
# with clang against 1630 s with GCC (0.83), and clang's build 1033 s against GCC's 1776 s (GCC's
# shared the machine with other work, so part of that gap is not the compiler's).
export CMAKE_GENERATOR="${CMAKE_GENERATOR:-Ninja}"  # as scripts/build.sh
cmake -S . -B build-sanitize -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DBLOCKDEM_BUILD_BENCH=OFF -DBLOCKDEM_PYTHON=OFF -DBLOCKDEM_MPI=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -fsanitize-address-use-after-return=never" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DBLOCKDEM_TEST_COSTS="$PWD/tests/costs/sanitized.txt" >/dev/null
stage "ASan build" cmake --build build-sanitize -j "$jobs"
# Left to the ordinary build (scripts/test.sh), which runs every test:
# - the install test: it builds a user's project against the installed library, and a sanitized
#   library needs a sanitized user (the documentation and Python tests skip themselves here);
# - the tests named in tests/sanitize_skip.txt: every coverage counter (a region), line and
#   branch arm of the library or the program that one of them reaches, a test here reaches too, so
#   the sanitizers check the same code without them. scripts/choose_sanitized_tests.py measures
#   that with a coverage build and writes the list; a test not named there runs here. A case of
#   a parameterised test is named without the printed parameter (` # GetParam() = ...`).
mapfile -t skip < <(grep -v -e '^#' -e '^$' tests/sanitize_skip.txt)
declare -A left_out
for name in "${skip[@]}"; do left_out["$name"]=1; done
selected=()
while IFS= read -r line; do
  number=${line%%:*}
  name=${line#*: }
  name=${name%%  # GetParam() = *}
  [[ $name == Install.* || -n ${left_out["$name"]:-} ]] || selected+=("$number")
done < <(ctest --test-dir build-sanitize -N | sed -n 's/^ *Test *#\([0-9]*: .*\)$/\1/p')
echo "sanitize: ${#selected[@]} tests under the sanitizers, ${#skip[@]} left to the ordinary run"
stage "ASan tests" ctest --test-dir build-sanitize --output-on-failure -j "$jobs" \
  -I "0,0,0,$(IFS=,; echo "${selected[*]}")"
