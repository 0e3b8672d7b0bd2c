#!/usr/bin/env bash
# Timed CLI runs of a generated scene at several sizes, both contact modes, 1 and 2 threads. The
# scene is the first argument:
#   pile      the 3D running-bond brick pile, bench/make_pile.py --n N (N cubes per side of a
#             layer; default sizes 10 32 100: about 1e3, 1e4, 1e5 blocks)
#   rockmass  the three-set rock mass, bench/make_rockmass.py --blocks N (about N blocks; default
#             sizes 1000 10000 100000)
# Each size runs with steps = 1 and steps = 11; the per-step cost is the difference / 10, which
# removes parsing, cutting, set-up and output. Prints one line per run with real and CPU (user +
# sys) seconds and peak RSS, from /usr/bin/time, and the contacts and blocks of summary.json; a
# run that fails prints its error instead of the figures.
#   bash bench/scale.sh pile|rockmass BLOCKDEM_BINARY WORK_DIR [size ...]
set -euo pipefail
scene=$1
case "$scene" in
  pile) generator=make_pile.py size_flag=--n label=n defaults=(10 32 100) ;;
  rockmass) generator=make_rockmass.py size_flag=--blocks label=rockmass defaults=(1000 10000 100000) ;;
  *)
    echo "bench/scale.sh: unknown scene '$scene' (pile or rockmass)" >&2
    exit 2
    ;;
esac
bin=$(readlink -f "$2")
work=$3
shift 3
sizes=("$@")
[ $# -eq 0 ] && sizes=("${defaults[@]}")
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
echo "# $(date -u +%FT%TZ) $(uptime)"
for n in "${sizes[@]}"; do
  for mode in boon2012 face_integrated; do
    for steps in 1 11; do
      toml="$work/${scene}_${n}_${mode}_s${steps}.toml"
      [ -f "$toml" ] || /usr/bin/python3 "$here/$generator" "$size_flag" "$n" --steps "$steps" --mode "$mode" >"$toml"
      for t in 1 2; do
        run="$label=$n mode=$mode steps=$steps threads=$t"
        out="$work/out_${scene}${n}_${mode}_s${steps}_t${t}"
        rm -rf "$out"
        log=$( (/usr/bin/time -f "$run real=%e user=%U sys=%S rss_kb=%M" \
          "$bin" run "$toml" --out "$out" --quiet --threads "$t" 2>&1 >/dev/null) || true)
        if [ -f "$out/summary.json" ]; then
          echo "$(grep "^$label=" <<<"$log") contacts=$(grep -m1 -o '"contacts": [0-9]*' "$out/summary.json" | grep -o '[0-9]*$') blocks=$(grep -o '"blocks": [0-9]*' "$out/summary.json" | grep -o '[0-9]*$')"
        else
          echo "$run FAILED: $(grep -m1 'error' <<<"$log")"
        fi
      done
    done
  done
done
echo "# $(date -u +%FT%TZ) $(uptime)"
