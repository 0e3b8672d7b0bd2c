#!/usr/bin/env bash
# Timed CLI runs of the 3D running-bond brick pile (bench/make_pile.py) at 1e3, 1e4, 1e5 blocks,
# both contact modes, 1 and 2 threads. Each size runs with steps = 1 and steps = 11; the per-step
# cost is the difference / 10, which removes parsing, set-up and output. Prints one line per run
# with real and CPU (user + sys) seconds and peak RSS, from /usr/bin/time.
#   bash bench/pile_scale.sh BLOCKDEM_BINARY WORK_DIR [n ...]     (default n: 10 32 100)
set -euo pipefail
bin=$(readlink -f "$1")
work=$2
shift 2
sizes=("${@:-10 32 100}")
[ $# -eq 0 ] && sizes=(10 32 100)
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
echo "# $(date -u +%FT%TZ) $(uptime)"
for n in "${sizes[@]}"; do
  for mode in boon2012 face_integrated; do
    for steps in 1 11; do
      toml="$work/pile_n${n}_${mode}_s${steps}.toml"
      [ -f "$toml" ] || /usr/bin/python3 "$here/make_pile.py" --n "$n" --steps "$steps" --mode "$mode" >"$toml"
      for t in 1 2; do
        out="$work/out_n${n}_${mode}_s${steps}_t${t}"
        rm -rf "$out"
        /usr/bin/time -f "n=$n mode=$mode steps=$steps threads=$t real=%e user=%U sys=%S rss_kb=%M" \
          "$bin" run "$toml" --out "$out" --quiet --threads "$t" 2>&1 >/dev/null | grep '^n=' |
          tr '\n' ' '
        echo "contacts=$(grep -m1 -o '"contacts": [0-9]*' "$out/summary.json" | tail -1 | grep -o '[0-9]*$') blocks=$(grep -o '"blocks": [0-9]*' "$out/summary.json" | grep -o '[0-9]*$')"
      done
    done
  done
done
echo "# $(date -u +%FT%TZ) $(uptime)"
