#!/bin/bash
# A rock mass of about a million blocks on one machine: generated, set up, settled under gravity
# and excavated, with the time of each part, the peak memory and the step rates at 1 and 2
# threads (bench/README.md, "A million blocks").
#
#   bash bench/million.sh build/blockdem /tmp/million [STEPS] [in-situ]
#
# The scene is bench/make_rockmass.py's three-set rock mass in a cube of 97.1 m (1 m spacing,
# mode face_integrated): about 949,000 blocks. Stages: STEPS steps of settling under gravity, then
# STEPS steps of a stage that excavates a horseshoe tunnel of radius 9.7 m along y through the
# cube's middle, both with density scaling (default STEPS = 20). A settling to equilibrium takes
# thousands of steps: the rates below tell how long. With `in-situ` the joints start with the
# geostatic stress (make_rockmass.py --in-situ): the rock mass is settled from the first step,
# every joint pressed, and the figures are those of a settled model.
set -euo pipefail
bin=$(realpath "$1")
out=$2
steps=${3:-20}
extra=()
[ "${4:-}" = "in-situ" ] && extra=(--in-situ)
here=$(cd "$(dirname "$0")" && pwd)
python=/usr/bin/python3
[ -x "$python" ] || python=python3
mkdir -p "$out"
cd "$out"
"$python" "$here/make_rockmass.py" --blocks 1300000 --max-blocks 3000000 --mode face_integrated \
  --steps "$steps" --excavate "$steps" --density-scaling "${extra[@]}" > million.toml
echo "load before: $(uptime)"

# Generation alone: the cut and its files (blocks.csv, faces.csv, blocks.vtk).
rm -rf generate
/usr/bin/time -f "%e %M" -o generate.time "$bin" generate million.toml --out generate --quiet \
  --no-figures
read -r wall rss < generate.time
echo "generate: $wall s wall, peak RSS $((rss / 1024)) MB"
rm -rf generate

for threads in 1 2; do
  rm -rf "run$threads"
  # A stage that does not reach equilibrium is not an error here (steps stages).
  /usr/bin/time -f "%e %M" -o "run$threads.time" "$bin" run million.toml --out "run$threads" \
    --no-figures --threads "$threads" 2> "run$threads.log" || true
  read -r wall rss < "run$threads.time"
  "$python" - "run$threads" "$threads" "$wall" "$rss" <<'EOF'
import json, re, sys
folder, threads, wall, rss = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
log = open(folder + ".log").read()
s = json.load(open(folder + "/summary.json"))
read = re.search(r"read .* in ([0-9.]+) s", log)
setup = re.search(r"set up .* in ([0-9.]+) s", log)
print(f"threads {threads}: {s['blocks']} blocks, wall {wall:.1f} s, peak RSS {rss // 1024} MB; "
      f"read and cut {read.group(1) if read else '<1'} s, set-up {setup.group(1) if setup else '<1'} s")
for k, st in enumerate(s["stages"]):
    # The stage's last status line: its rate since the stage started.
    lines = re.findall(r"\[%d/\d+\] [^\n]*?step (\d+),[^\n]*?, ([0-9.e+]+) steps/s" % (k + 1), log)
    if not lines:
        print(f"  {st['name']}: {st['steps']} steps, no status line")
        continue
    step, rate = int(lines[-1][0]), float(lines[-1][1])
    print(f"  {st['name']}: {st['steps']} steps, {st['contacts']} contacts at its end, "
          f"{rate:.3g} steps/s at step {step} = {rate * st['contacts'] / 1e6:.2f} M contact "
          f"updates per second")
EOF
done
echo "load after: $(uptime)"
