#!/usr/bin/env bash
# Peak resident memory per process of one scenario run on 1, 2, 3 ... MPI processes: while the
# process set up (read the scene, built the world) and while it ran the stages
# (`blockdem run --memory-report`), and its whole peak (`/usr/bin/time`), each against one
# process. One thread per process, passive OpenMP waiting.
#   bash bench/memory_ranks.sh BLOCKDEM_BINARY SCENARIO WORK_DIR [ranks ...]   (default 1 2 3)
# Example (the 1e5-block rock mass of docs/scaling.md, "Memory"):
#   /usr/bin/python3 bench/make_rockmass.py --blocks 100000 --steps 1 > /tmp/rm.toml
#   bash bench/memory_ranks.sh build/blockdem /tmp/rm.toml /tmp/mem
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,8p' "$0" >&2
  exit 2
fi
bin=$(readlink -f "$1")
scenario=$(readlink -f "$2")
work=$3
shift 3
ranks=("$@")
[ ${#ranks[@]} -gt 0 ] || ranks=(1 2 3)
mkdir -p "$work"
echo "# $(date -u '+%F %T') UTC, $(uptime | sed 's/.*load/load/'), $bin"
echo "| processes | set-up peak per process (MiB) | after the set-up (MiB) | run peak per process (MiB) | whole peak (MiB) | run peak / one process's |"
echo "|---|---|---|---|---|---|"
one=""
for k in "${ranks[@]}"; do
  rm -rf "$work/out$k" "$work/time$k".* "$work/log$k.txt"
  OMP_WAIT_POLICY=passive OMP_NUM_THREADS=1 mpirun --oversubscribe --allow-run-as-root \
    -x OMP_WAIT_POLICY -x OMP_NUM_THREADS -np "$k" sh -c \
    '/usr/bin/time -f "%M" -o "$0.$OMPI_COMM_WORLD_RANK" "$@"' "$work/time$k" \
    "$bin" run "$scenario" --out "$work/out$k" --threads 1 --quiet --no-figures --memory-report \
    2> "$work/log$k.txt" || [ $? -eq 3 ] || { cat "$work/log$k.txt" >&2; exit 1; }
  # "blockdem: process R of K: peak resident memory A MiB while setting up (...; C MiB after
  # it), B MiB while running the stages"
  setup=$(grep -o 'memory [0-9.]* MiB while setting' "$work/log$k.txt" | awk '{print $2}' | sort -n | paste -sd/)
  after=$(grep -o '; [0-9.]* MiB after it' "$work/log$k.txt" | awk '{print $2}' | sort -n | paste -sd/)
  run=$(grep -o ', [0-9.]* MiB while running' "$work/log$k.txt" | awk '{print $2}' | sort -n | paste -sd/)
  whole=$(for f in "$work/time$k".*; do awk '{printf "%.1f\n", $1 / 1024}' "$f"; done | sort -n | paste -sd/)
  top=$(echo "$run" | tr / '\n' | sort -n | tail -1)
  [ -n "$one" ] || one=$top
  echo "| $k | $setup | $after | $run | $whole | $(awk -v a="$top" -v b="$one" 'BEGIN {printf "%.2f", a / b}') |"
done
