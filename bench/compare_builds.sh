#!/usr/bin/env bash
# Two builds of `blockdem` on the same examples, in the same hour: each example run with the build
# before and the build after, the two alternated, REPEATS times each. Prints per example and build
# the median wall time of the whole run (`summary.json`'s wall_time_s: set-up and outputs
# included, no figures), the ratio before / after, and whether the two builds' CSV files are the
# same bytes (`cmp`; a change meant to leave the results alone must print "same").
#
#   bash bench/compare_builds.sh BEFORE AFTER [REPEATS] [THREADS] [EXAMPLE...]
#
# BEFORE and AFTER are paths to `blockdem` programs (say, a copy of build/blockdem made before
# the change, and build/blockdem). Defaults: 3 repeats, 2 threads, the bolted examples
# (slope_bolted, tunnel_bolted, roof_wedge_bolted).
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { sed -n 2,12p "$0"; exit 2; }
before=$(realpath "$1")
after=$(realpath "$2")
repeats=${3:-3}
threads=${4:-2}
shift $(($# > 4 ? 4 : $#))
examples=("$@")
[ ${#examples[@]} -gt 0 ] || examples=(slope_bolted tunnel_bolted roof_wedge_bolted)
python=/usr/bin/python3
[ -x "$python" ] || python=python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "load at the start: $(uptime | sed 's/.*load average: //'); $repeats repeats, $threads threads"
for ex in "${examples[@]}"; do
  declare -A walls=()
  for ((r = 0; r < repeats; ++r)); do
    for build in before after; do
      bin=$before
      [ "$build" = after ] && bin=$after
      out=$work/$ex-$build
      rm -rf "$out"
      "$bin" run "scenarios/examples/$ex.toml" --out "$out" --quiet --no-figures \
        --threads "$threads" >/dev/null 2>&1 || true
      walls[$build]+="$("$python" -c "import json;print(json.load(open('$out/summary.json'))['wall_time_s'])") "
    done
  done
  same=same
  for f in "$work/$ex-before"/*.csv; do
    cmp -s "$f" "$work/$ex-after/$(basename "$f")" || same="differ ($(basename "$f"))"
  done
  "$python" - "$ex" "${walls[before]}" "${walls[after]}" "$same" <<'EOF'
import statistics, sys
ex, before, after, same = sys.argv[1], sys.argv[2].split(), sys.argv[3].split(), sys.argv[4]
b = statistics.median(float(x) for x in before)
a = statistics.median(float(x) for x in after)
print(f"{ex}: median wall before {b:.2f} s, after {a:.2f} s, before / after {b / a:.2f}; "
      f"CSV files {same}  (before {' '.join(before)}; after {' '.join(after)})")
EOF
  unset walls
done
echo "load at the end: $(uptime | sed 's/.*load average: //')"
