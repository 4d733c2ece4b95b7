#!/usr/bin/env bash
# Speed of DynamO and haff on the sheared granular gas of bench/peers/dynamo_shear.sh, on one
# core, interleaved: each repeat runs DynamO's dynarun (its Misc plugin on, as in
# dynamo_shear.sh), dynarun -E (no output plugin: the bare engine) and `haff run` (with its
# 100 samples of the pressure tensor), one after the other, pinned with taskset.
#
#   bench/peers/dynamo_speed.sh [PARTICLES] [PACKING_FRACTION] [RATE] [RESTITUTION]
#                               [COLLISIONS_PER_PARTICLE] [REPEATS] [CORE]
#
# Defaults: N = 2000, phi = 0.01, a = 0.04, alpha = 0.9, 200 collisions per particle
# (cpp N / 2 collisions, from the same start: T = 1 plus the flow), 3 repeats, core 1.
# Rates: collisions per second of the whole process (wall clock, start-up and output
# included) for all three; also DynamO's Misc "EventsPerSec" (DynamO counts collisions as
# events: cell crossings and its PBC sentinel's virtual events are not counted) and haff's
# collisions_per_second / events_per_second (its events include cell crossings). Prints
# each repeat, the medians and the ratios haff / DynamO.
set -euo pipefail
particles=${1:-2000}
phi=${2:-0.01}
rate=${3:-0.04}
alpha=${4:-0.9}
cpp=${5:-200}
repeats=${6:-3}
core=${7:-1}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
usf="python3 $here/dynamo_usf.py"
bin=$("$here/dynamo.sh" build)
haff=${HAFF_BIN:-}
if [ -z "$haff" ]; then
    for h in "$root/target/t2/release/haff" "$root/target/release/haff" "$root/target/peer/release/haff"; do
        [ -x "$h" ] && { haff=$h; break; }
    done
fi
if [ -z "$haff" ]; then
    (cd "$root" && CARGO_TARGET_DIR=target/peer nice -n 19 cargo build --release -p haff-cli)
    haff=$root/target/peer/release/haff
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cd "$scratch"
density=$(python3 -c "import math; print(repr(6 * $phi / math.pi))")
read -r cx cy cz <<<"$($usf cells "$particles")"
total=$(python3 -c "print(round($cpp * $particles / 2))")
"$bin/dynamod" -m 4 -x "$cx" -y "$cy" -z "$cz" -d "$density" --f1 "$alpha" -s 3 \
    -o lattice.xml > dynamod.log 2>&1
$usf prepare lattice.xml start.xml --rate "$rate" --alpha "$alpha" --temperature 1.0 --seed 3
cat > haff.toml <<TOML
[system]
dimension = 3
particles = $particles
packing_fraction = $phi
temperature = 1.0
seed = 3
[collision]
law = "constant"
restitution = $alpha
[run]
engine = "event-driven"
collisions_per_particle = $cpp
samples = 100
spacing = "linear"
[shear]
rate = $rate
TOML
now() { date +%s.%N; }
rows=()
for r in $(seq "$repeats"); do
    t0=$(now)
    taskset -c "$core" "$bin/dynarun" start.xml -c "$total" -o end.xml --out-data-file out.xml > misc.log 2>&1
    t1=$(now)
    taskset -c "$core" "$bin/dynarun" start.xml -c "$total" -E -o end.E.xml > bare.log 2>&1
    t2=$(now)
    taskset -c "$core" "$haff" run haff.toml --out haff --force > haff.log 2>&1
    t3=$(now)
    row=$(python3 - "$t0" "$t1" "$t2" "$t3" <<PY
import json, sys, xml.etree.ElementTree as ET
t0, t1, t2, t3 = map(float, sys.argv[1:])
misc = ET.parse("out.xml").getroot().find("Misc")
coll = sum(int(e.get("Count")) for e in misc.iter("Entry")
           if e.get("Type") == "Interaction" and e.get("Event") == "CORE")
loop = float(misc.find("Timing").get("EventsPerSec"))
h = json.load(open("haff/summary.json"))
print(json.dumps({"dynamo_wall": t1 - t0, "dynamo_cps_wall": coll / (t1 - t0),
                  "dynamo_cps_loop": loop, "dynamo_E_wall": t2 - t1,
                  "dynamo_E_cps_wall": $total / (t2 - t1), "haff_wall": t3 - t2,
                  "haff_cps_wall": h["collisions"] / (t3 - t2),
                  "haff_cps": h["collisions_per_second"], "haff_eps": h["events_per_second"],
                  "haff_events_per_collision": h["events"] / h["collisions"],
                  "collisions": coll}))
PY
)
    rows+=("$row")
    echo "repeat $r: $row"
done
python3 - "${rows[@]}" <<PY
import json, statistics, sys
rows = [json.loads(x) for x in sys.argv[1:]]
med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
print(f"N = $particles, phi = $phi, a = $rate, alpha = $alpha, {med['collisions']:.0f} collisions, core $core, medians of $repeats:")
print(f"  DynamO (Misc on):  {med['dynamo_wall']:.2f} s wall, {med['dynamo_cps_wall']:.3e} collisions/s (wall), {med['dynamo_cps_loop']:.3e} (Misc EventsPerSec)")
print(f"  DynamO -E:         {med['dynamo_E_wall']:.2f} s wall, {med['dynamo_E_cps_wall']:.3e} collisions/s (wall)")
print(f"  haff run:          {med['haff_wall']:.2f} s wall, {med['haff_cps_wall']:.3e} collisions/s (wall), {med['haff_cps']:.3e} (summary), {med['haff_eps']:.3e} events/s, {med['haff_events_per_collision']:.1f} events/collision")
print(f"  ratio haff/DynamO, collisions per wall second: {med['haff_cps_wall'] / med['dynamo_cps_wall']:.2f} (Misc on), {med['haff_cps_wall'] / med['dynamo_E_cps_wall']:.2f} (-E)")
print("JSON " + json.dumps(med))
PY
