#!/usr/bin/env bash
# How a strength reduction places its trials: each example run with `factor_search = "bisect"`
# (every trial at the bracket's midpoint) and "extrapolate" (the default: trials placed by the
# critical factor extrapolated from the failed trials' accelerations, docs/stability.md), the
# two alternated, REPEATS times each. Prints per example and search the bracket, the estimate,
# the trials, the steps of the search and of the whole run, and the median wall time of the whole
# run (`summary.json`'s wall_time_s, set-up and outputs included; no figures).
#
#   bash bench/fos_search.sh [REPEATS] [THREADS] [EXAMPLE...]
#
# Defaults: 3 repeats, 1 thread, slope_fos, roof_wedge and planar_sliding (examples that name no
# other file, so that their copies with the key run from a temporary folder).
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
threads=${2:-1}
shift $(($# > 2 ? 2 : $#))
examples=("$@")
[ ${#examples[@]} -gt 0 ] || examples=(slope_fos roof_wedge planar_sliding)
bin=build/blockdem
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "load: $(uptime | sed 's/.*load average: //')"
for ex in "${examples[@]}"; do
  src=scenarios/examples/$ex.toml
  for search in bisect extrapolate; do
    # The search key goes into the strength-reduction stage (the file's last stage).
    awk -v s="$search" '{print} /^kind = "strength_reduction"/ {print "factor_search = \"" s "\""}' \
      "$src" >"$work/$ex-$search.toml"
  done
  declare -A walls=()
  for ((r = 0; r < repeats; ++r)); do
    for search in bisect extrapolate; do
      out=$work/$ex-$search
      rm -rf "$out"
      "$bin" run "$work/$ex-$search.toml" --out "$out" --quiet --no-figures \
        --threads "$threads" >/dev/null 2>&1 || true
      walls[$search]+="$(/usr/bin/python3 -c "import json;print(json.load(open('$out/summary.json'))['wall_time_s'])") "
    done
  done
  for search in bisect extrapolate; do
    out=$work/$ex-$search
    /usr/bin/python3 - "$out/summary.json" "$ex" "$search" ${walls[$search]} <<'PY'
import json, statistics, sys
s = json.load(open(sys.argv[1]))
f = s["factor_of_safety"]
steps = sum(t["steps"] for t in f["trials"])
est = f["extrapolated"]
walls = [float(w) for w in sys.argv[4:]]
print(f"{sys.argv[2]:15s} {sys.argv[3]:11s} [{f['last_stable']:.5g}, {f['first_failed']:.5g}] "
      f"F = {f['value']:.5g}, estimate {'-' if est is None else format(est, '.5g')}, "
      f"{len(f['trials'])} trials, {steps} steps of the search (the other stages {s['steps']}), wall {statistics.median(walls):.2f} s "
      f"(runs: {' '.join(format(w, '.2f') for w in walls)})")
PY
  done
  unset walls
done
echo "load: $(uptime | sed 's/.*load average: //')"
