#!/usr/bin/env bash
# How OpenMP's waiting threads share a busy machine: the tunnel rock mass with half its joint
# spacing (253 blocks), a fixed number of steps, at 1 and 2 threads, on the machine as it is
# ("quiet") and beside one CPU-bound process (`yes > /dev/null`, "loaded"), under each waiting
# policy given. Prints one line per case with the median wall time of the runs (s).
#
#   bash bench/wait_policy.sh [REPEATS] [STEPS] [POLICY...]
#
# A POLICY is an environment assignment for the run ("GOMP_SPINCOUNT=300000": the OpenMP
# library's own default, threads spin about 0.3 ms at a barrier before they sleep;
# "OMP_WAIT_POLICY=passive": they sleep at once) or "default" (the program's own choice,
# docs/architecture.md). Defaults: 5 repeats, 1000 steps per stage, the three policies.
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-5}
steps=${2:-1000}
shift $(($# > 2 ? 2 : $#))
policies=("$@")
[ ${#policies[@]} -gt 0 ] || policies=(default GOMP_SPINCOUNT=300000 OMP_WAIT_POLICY=passive)
bin=build/blockdem
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Half the joint spacing of the shipped example: 253 blocks.
sed -e 's/^spacing = 2.6/spacing = 1.3/' -e 's/^spacing = 3.1/spacing = 1.55/' \
  -e 's/^spacing = 3.4/spacing = 1.7/' scenarios/examples/tunnel.toml >"$work/tunnel_half.toml"

# The median of the wall times given as arguments.
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

# One run's wall time (s) under policy $1 with $2 threads.
one_run() {
  local policy=$1 threads=$2 t0 t1
  t0=$(date +%s.%N)
  if [ "$policy" = default ]; then
    env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$bin" run "$work/tunnel_half.toml" \
      --out "$work/out" --quiet --no-figures --max-steps "$steps" --threads "$threads" 2>/dev/null || true
  else
    env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$policy" "$bin" run "$work/tunnel_half.toml" \
      --out "$work/out" --quiet --no-figures --max-steps "$steps" --threads "$threads" 2>/dev/null || true
  fi
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc
}

for load in quiet loaded; do
  hog=""
  if [ "$load" = loaded ]; then
    yes >/dev/null &
    hog=$!
  fi
  for policy in "${policies[@]}"; do
    for threads in 1 2; do
      times=()
      for _ in $(seq "$repeats"); do times+=("$(one_run "$policy" "$threads")"); done
      printf '%-7s %-26s threads %d: median %.2f s (%s)\n' "$load" "$policy" "$threads" \
        "$(median "${times[@]}")" "${times[*]}"
    done
  done
  [ -n "$hog" ] && kill "$hog"
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
