#!/usr/bin/env bash
# SPARTA (serial build) side by side with `haff bench dsmc --scheme spatial` on one core: an
# elastic hard-sphere gas in a periodic box, N simulated particles, 15.6 per collision cell,
# time step a fifth of the mean free time.
#
#   bench/peers/sparta_box.sh SPARTA_SRC [PARTICLES] [REPEATS] [CORE]
#
# SPARTA_SRC is the src/ directory of a checkout of https://github.com/sparta/sparta (its
# public source; nothing of it is copied into haff), built here with `make serial` if
# spa_serial is missing. Hard spheres are SPARTA's VSS model with omega = 0.5, alpha = 1
# (argon-like mass and diameter at 273.15 K, n = 1e20 m^-3; cells a third of the mean free
# path wide). Each repeat runs SPARTA in both its configurations, with its speed options
# and with its defaults (20 steps of warm-up, then 100 timed: 20 collisions per particle),
# and haff (1 collision per particle of warm-up, 20 timed), one after the other on the same
# core; the rates are collisions per CPU-second of the timed part (SPARTA's "Loop time",
# its mean Ncoll per step from stats every 10 steps; haff's bench JSON). It prints the
# medians and haff's ratio to each configuration. SPARTA_OPTIONS="..." runs SPARTA in that
# one configuration only.
set -euo pipefail
src=$(cd "${1:?usage: $0 SPARTA_SRC [PARTICLES] [REPEATS] [CORE]}" && pwd)
particles=${2:-1000000}
repeats=${3:-3}
core=${4:-1}
# SPARTA's own speed options (docs/global): particles re-ordered by cell every 10 steps and
# the single-step move of a uniform grid without surfaces; both off by default in SPARTA,
# both faster here. The configurations: name and options.
if [ -n "${SPARTA_OPTIONS+set}" ]; then
    configurations=("given:$SPARTA_OPTIONS")
else
    configurations=("fast:particle/reorder 10 optmove yes" "defaults:")
fi
root=$(cd "$(dirname "$0")/../.." && pwd)
haff=${HAFF_BIN:-$root/target/release/haff}
[ -x "$src/spa_serial" ] || (cd "$src" && make serial -j2 >/dev/null)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cd "$scratch"
echo "Ar 39.948 6.63e-26 0 0 0 0 0 1 0" > box.species
echo "Ar 4.17e-10 0.5 273.15 1.0" > box.vss
read -r cells side fnum dt <<<"$(python3 -c "
import math
n, d, m, k, T, N = 1e20, 4.17e-10, 6.63e-26, 1.380649e-23, 273.15, $particles
per_cell = 15.6
cells = round((N / per_cell) ** (1 / 3))
mfp = 1 / (math.sqrt(2) * math.pi * d * d * n)
side = cells * mfp / 3
mean_speed = math.sqrt(8 * k * T / (math.pi * m))
print(cells, side, n * side ** 3 / N, mfp / mean_speed / 5)")"
# The input deck of one configuration: in.NAME.
write_input() {
    cat > "in.$1" <<IN
seed 12345
dimension 3
global nrho 1.0e20 fnum $fnum $2
boundary p p p
create_box 0 $side 0 $side 0 $side
create_grid $cells $cells $cells
balance_grid rcb cell
species box.species Ar
mixture gas Ar vstream 0 0 0 temp 273.15
collide vss gas box.vss
create_particles gas n $particles
timestep $dt
stats 10
stats_style step cpu np nattempt ncoll
run 20
run 100
IN
}
for c in "${configurations[@]}"; do
    write_input "${c%%:*}" "${c#*:}"
done
declare -A sparta
ours=()
for r in $(seq "$repeats"); do
    line="repeat $r:"
    for c in "${configurations[@]}"; do
        name=${c%%:*}
        out=$(taskset -c "$core" "$src/spa_serial" -in "in.$name")
        rate=$(echo "$out" | python3 -c '
import sys
text = sys.stdin.read()
runs = text.split("Step CPU Np Natt Ncoll")
rows = [l.split() for l in runs[2].splitlines()[1:] if l.strip() and l.split()[0].isdigit()]
per_step = sum(int(r[4]) for r in rows[1:]) / len(rows[1:])
loop = float(text.split("Loop time of")[2].split()[0])
print(per_step * 100 / loop)')
        sparta[$name]="${sparta[$name]:-} $rate"
        line="$line SPARTA ($name) $rate,"
    done
    json=$(taskset -c "$core" "$haff" bench dsmc --scheme spatial --particles "$particles" \
        --law 1 --threads 1 --collisions 20 --repeats 1 --format json)
    ours+=("$(echo "$json" | python3 -c 'import json,sys; print(json.load(sys.stdin)["collisions_per_second"])')")
    echo "$line haff ${ours[-1]} collisions per CPU-second"
done
summary=()
for c in "${configurations[@]}"; do
    name=${c%%:*}
    summary+=("$name=${sparta[$name]# }")
done
python3 - "${ours[*]}" "${summary[@]}" <<PY
import statistics, sys
o = statistics.median(float(x) for x in sys.argv[1].split())
print(f"N = $particles, 15.6 per cell, dt = tau/5, core $core, medians of $repeats: haff {o:.3e} collisions per CPU-second")
for entry in sys.argv[2:]:
    name, values = entry.split("=", 1)
    s = statistics.median(float(x) for x in values.split())
    print(f"  SPARTA ({name}) {s:.3e}, ratio haff/SPARTA = {o / s:.2f}")
PY
