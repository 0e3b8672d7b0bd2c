#!/usr/bin/env bash
# Builds the tests with ThreadSanitizer in build-tsan/ (clang and LLVM's OpenMP runtime, whose
# Archer tool tells ThreadSanitizer about OpenMP's barriers and tasks; libgomp is not
# instrumented and would report its own synchronisation as races) and runs the tests that step
# a world on several threads. Any data race fails the run. Prints the build's and the tests'
# times (scripts/stage_time.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage_time.sh
bash scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
llvm=$(ls -d /usr/lib/llvm-*/lib | sort -V | tail -1)
# The threaded tests, by file (only these are compiled: building every test with ThreadSanitizer
# took most of this script's time): the step on 1, 2 and 3 threads (with bolts too), restarts
# with 2 threads and their signals, a restart that continues on 3 threads, the broad phase's
# threaded pair search, and the worlds distributed over threads standing in for processes (their
# exchanges, stages, checkpoints and a failure inside a step), and a rock mass cut, made into
# blocks and written on several threads, and the one-process step's pairs found by ranges of
# blocks on several threads and the pair store merged from their changes. A file that gains a threaded test is added here.
threaded='/(parallel_determinism|parallel_cut|restart|restart_signal|world_state|broad_phase|distributed_step|distributed_stage|step_failure|pair_ranges|pair_changes)_test[.]cpp$'
# -O1 and line tables only, as in scripts/sanitize.sh: reports still name file and line.
export CMAKE_GENERATOR="${CMAKE_GENERATOR:-Ninja}"  # as scripts/build.sh
CXX=clang++ cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBLOCKDEM_BUILD_BENCH=OFF \
  -DBLOCKDEM_PYTHON=OFF -DBLOCKDEM_MPI=OFF -DBLOCKDEM_TEST_SOURCES_REGEX="$threaded" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" >/dev/null
stage "TSan build" cmake --build build-tsan -j "$jobs" --target blockdem_tests blockdem
export OMP_TOOL_LIBRARIES="$llvm/libarcher.so"
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 ignore_noninstrumented_modules=1"
# Tests whose length serves only their timing or breadth run shorter (tests/support/sanitized_run.hpp).
export BLOCKDEM_TEST_SANITIZED=1
stage "TSan tests" build-tsan/blockdem_tests
