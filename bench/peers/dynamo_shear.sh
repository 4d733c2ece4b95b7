#!/usr/bin/env bash
# A sheared granular gas in DynamO and in haff side by side: 3D smooth inelastic hard
# spheres, constant restitution, Lees-Edwards boundaries, steady uniform shear flow without
# thermostat (the viscous heating balances the collisional cooling).
#
#   bench/peers/dynamo_shear.sh OUTDIR [PARTICLES] [PACKING_FRACTION] [RESTITUTION] [RATE]
#                               [COLLISIONS_PER_PARTICLE] [SAMPLES] [SEEDS]
#
# Defaults: N = 2000, phi = 0.01, alpha = 0.9, a = 0.04, 200 collisions per particle
# (collisions = that * N / 2, haff's count), 100 samples, seed 3 (SEEDS: one, or a comma list such as 3,4,5,6,7: a run of each
# code per seed in OUTDIR/seed.S, the table from the scatter of the seeds' means). Units: sigma = m = 1,
# initial T = 1 (Maxwellian peculiar velocities plus the flow a y e_x).
#
# DynamO (built by bench/peers/dynamo.sh): `dynamod -m 4` (inelastic hard spheres in LEBC)
# with FCC cells 4 X Y Z = N in a cubic box at number density n = 6 phi / pi; then
# dynamo_usf.py prepare sets the BC's Rate, the interaction's Elasticity and the velocities;
# then dynarun runs SAMPLES segments of (collisions / SAMPLES) collisions each, each from
# the configuration the previous one wrote (its Misc output: the collisional pressure
# averaged over the segment; its end configuration: the kinetic pressure from the peculiar
# velocities and T). No thermostat (dynamod -m 4 adds none). Means over the second half
# (segments SAMPLES/2+1 .. SAMPLES), errors from 10 batch means: OUTDIR/dynamo/summary.json,
# OUTDIR/dynamo/timeseries.csv.
# haff (HAFF_BIN, default target/t2/release/haff, else target/release/haff): the same case
# as a run file OUTDIR/haff.toml, `haff run` into OUTDIR/haff. Prints the table of both.
set -euo pipefail
usage="usage: $0 OUTDIR [PARTICLES] [PACKING_FRACTION] [RESTITUTION] [RATE] [COLLISIONS_PER_PARTICLE] [SAMPLES] [SEEDS]"
out=${1:?$usage}
particles=${2:-2000}
phi=${3:-0.01}
alpha=${4:-0.9}
rate=${5:-0.04}
cpp=${6:-200}
samples=${7:-100}
seeds=${8:-3}
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
(( samples % 2 == 0 )) || { echo "SAMPLES must be even" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
IFS=, read -r -a seed_list <<<"$seeds"
density=$(python3 -c "import math; print(repr(6 * $phi / math.pi))")
read -r cx cy cz <<<"$($usf cells "$particles")"
total=$(python3 -c "print(round($cpp * $particles / 2))")
per=$(( total / samples ))
dsum=() hsum=()
for seed in "${seed_list[@]}"; do
    if [ ${#seed_list[@]} = 1 ]; then o=$out; else o=$out/seed.$seed; fi
    d=$o/dynamo
    mkdir -p "$d"

    # (a) the configuration
    "$bin/dynamod" -m 4 -x "$cx" -y "$cy" -z "$cz" -d "$density" --f1 "$alpha" -s "$seed" \
        -o "$d/config.lattice.xml" > "$d/dynamod.log" 2>&1
    $usf prepare "$d/config.lattice.xml" "$d/seg.0.config.xml" --rate "$rate" \
        --alpha "$alpha" --temperature 1.0 --seed "$seed"

    # (b) the run, in segments (the Misc plugin is on by default; no thermostat)
    start=$(date +%s.%N)
    for k in $(seq "$samples"); do
        "$bin/dynarun" "$d/seg.$((k - 1)).config.xml" -c "$per" -o "$d/seg.$k.config.xml" \
            --out-data-file "$d/seg.$k.output.xml" > "$d/seg.$k.log" 2>&1
    done
    end=$(date +%s.%N)
    echo "seed $seed: DynamO $samples segments of $per collisions in $(python3 -c "print(round($end - $start, 2))") s"

    # (c) the steady state: second half
    $usf analyse "$d" --rate "$rate" --first $(( samples / 2 + 1 )) --last "$samples" \
        --timeseries "$d/timeseries.csv" > "$d/summary.json"

    # haff, the same case
    cat > "$o/haff.toml" <<TOML
[system]
dimension = 3
particles = $particles
packing_fraction = $phi
temperature = 1.0
seed = $seed
[collision]
law = "constant"
restitution = $alpha
[run]
engine = "event-driven"
collisions_per_particle = $cpp
samples = $samples
spacing = "linear"
[shear]
rate = $rate
TOML
    "$haff" run "$o/haff.toml" --out "$o/haff" --force > "$o/haff.log" 2>&1
    dsum+=("$d/summary.json")
    hsum+=("$o/haff/summary.json")
done
join() { local IFS=,; echo "$*"; }
echo "N = $particles, phi = $phi, alpha = $alpha, a = $rate, $cpp collisions per particle, seeds $seeds, second half:"
$usf table "$(join "${dsum[@]}")" "$(join "${hsum[@]}")" | tee "$out/table.md"
