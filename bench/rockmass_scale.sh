#!/usr/bin/env bash
# Timed CLI runs of the three-set rock mass (bench/make_rockmass.py) at about 1e3, 1e4, 1e5
# blocks, both contact modes, 1 and 2 threads: the loop of bench/pile_scale.sh on another scene.
# Each size runs with steps = 1 and steps = 11; the per-step cost is the difference / 10, which
# removes parsing, cutting, set-up and output. Prints one line per run with real and CPU
# (user + sys) seconds and peak RSS, from /usr/bin/time.
#   bash bench/rockmass_scale.sh BLOCKDEM_BINARY WORK_DIR [blocks ...]   (default 1000 10000 100000)
set -euo pipefail
bin=$(readlink -f "$1")
work=$2
shift 2
sizes=("$@")
[ $# -eq 0 ] && sizes=(1000 10000 100000)
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
echo "# $(date -u +%FT%TZ) $(uptime)"
for n in "${sizes[@]}"; do
  for mode in boon2012 face_integrated; do
    for steps in 1 11; do
      toml="$work/rockmass_${n}_${mode}_s${steps}.toml"
      [ -f "$toml" ] || /usr/bin/python3 "$here/make_rockmass.py" --blocks "$n" --steps "$steps" --mode "$mode" >"$toml"
      for t in 1 2; do
        out="$work/out_rm${n}_${mode}_s${steps}_t${t}"
        rm -rf "$out"
        log=$( (/usr/bin/time -f "rockmass=$n mode=$mode steps=$steps threads=$t real=%e user=%U sys=%S rss_kb=%M" \
          "$bin" run "$toml" --out "$out" --quiet --threads "$t" 2>&1 >/dev/null) || true)
        # A run that fails prints its error instead of the figures.
        if [ -f "$out/summary.json" ]; then
          echo "$(grep '^rockmass=' <<<"$log") contacts=$(grep -m1 -o '"contacts": [0-9]*' "$out/summary.json" | grep -o '[0-9]*$') blocks=$(grep -o '"blocks": [0-9]*' "$out/summary.json" | grep -o '[0-9]*$')"
        else
          echo "rockmass=$n mode=$mode steps=$steps threads=$t FAILED: $(grep -m1 'error' <<<"$log")"
        fi
      done
    done
  done
done
echo "# $(date -u +%FT%TZ) $(uptime)"
