#!/usr/bin/env bash
# Rough hard spheres in DynamO and in haff side by side: the homogeneous cooling state (HCS)
# of a 3D gas of solid spheres (q = 2/5), constant normal restitution alpha and tangential
# restitution beta (haff's convention g_t' = -beta g_t; DynamO's TangentialElasticity is
# e_t = -beta, see dynamo_rough.py), and the speed of both on one core.
#
#   bench/peers/dynamo_rough.sh hcs OUTDIR [PARTICLES] [PACKING_FRACTION]
#                                   [COLLISIONS_PER_PARTICLE] [SEEDS] [CASES] [TROT]
#   bench/peers/dynamo_rough.sh speed OUTDIR [PARTICLES] [PACKING_FRACTION] [ALPHA] [BETA]
#                                   [COLLISIONS_PER_PARTICLE] [REPEATS] [CORE]
#
# hcs defaults: N = 4000, phi = 0.02, 40 collisions per particle (haff's count: 2 C / N),
# seeds 1,2,3, CASES "0.9:0.0 0.9:0.5 0.7:0.0 0.7:0.5" (alpha:beta), TROT 0. Start:
# sigma = m = 1, T_tr = 1 (Gaussian velocities, momentum zero, rescaled exactly), T_rot = TROT
# (0: spheres at rest; a number: Gaussian angular velocities rescaled to I <w^2> / 3 = TROT;
# "theory": the case's Maxwellian HCS ratio), in both codes. For each case and seed:
#   DynamO (built by bench/peers/dynamo.sh): `dynamod -m 0` with FCC cells 4 X Y Z = N in a
#   cubic box at number density n = 6 phi / pi, --f1 alpha --f2=-beta (rough spheres: a
#   SphericalTop species and orientation data); dynamo_rough.py prepare sets the velocities,
#   angular velocities, Elasticity, TangentialElasticity and InertiaConstant (0.1 = 2/5 (d/2)^2);
#   dynarun runs CPP segments of N/2 collisions (one collision per particle) each, each from
#   the configuration the previous wrote; dynamo_rough.py analyse -> dynamo/timeseries.csv.
#   haff (HAFF_BIN, default target/t2/release/haff, else target/release/haff): the same case
#   as OUTDIR/a*_b*/seed.S/haff.toml, `haff run` -> haff/timeseries.csv (CPP + 1 linear
#   samples: the start and every collision per particle, as DynamO's segments).
# Then dynamo_rough.py table: T_rot/T_tr averaged over the samples at 20..40 collisions per
# particle and the slope of -ln T_tr against collisions per particle there (least squares),
# mean ± standard error over the seeds, with the Maxwellian theory. OUTDIR/table.md.
#
# speed defaults: N = 20000, phi = 0.02, alpha = 0.9, beta = 0.5, 20 collisions per particle,
# 3 repeats, core 1. One start (seed 1) for both codes; each repeat runs dynarun (Misc on),
# dynarun -E (no output plugin) and haff run (20 samples) one after the other under
# taskset -c CORE. Rates: collisions per wall-clock second and per CPU second (user + sys,
# /usr/bin/time) of the whole process (start-up, XML input and output included); medians.
# `uptime` is printed before and after each repeat: time on a quiet machine.
set -euo pipefail
usage="usage: $0 hcs OUTDIR [N] [PHI] [CPP] [SEEDS] [CASES] [TROT] | speed OUTDIR [N] [PHI] [ALPHA] [BETA] [CPP] [REPEATS] [CORE]"
mode=${1:?$usage}
out=${2:?$usage}
shift 2
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
rough="python3 $here/dynamo_rough.py"
bin=$("$here/dynamo.sh" build)
haff=${HAFF_BIN:-}
if [ -z "$haff" ]; then
    for h in "$root/target/t2/release/haff" "$root/target/release/haff"; do
        [ -x "$h" ] && { haff=$h; break; }
    done
fi
[ -n "$haff" ] || { echo "no haff binary (set HAFF_BIN)" >&2; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)

haff_toml() { # FILE N PHI SEED ALPHA BETA CPP SAMPLES [TROT]
    cat > "$1" <<TOML
[system]
dimension = 3
particles = $2
packing_fraction = $3
temperature = 1.0
seed = $4
inertia = 0.4
rotational_temperature = ${9:-0.0}
[collision]
law = "constant"
restitution = $5
tangential_restitution = $6
[run]
engine = "event-driven"
collisions_per_particle = $7
samples = $8
spacing = "linear"
TOML
}

dynamo_start() { # DIR N PHI SEED ALPHA BETA [TROT] -> DIR/seg.0.config.xml
    local d=$1 n=$2 phi=$3 seed=$4 alpha=$5 beta=$6 trot=${7:-0.0} density cx cy cz
    density=$(python3 -c "import math; print(repr(6 * $phi / math.pi))")
    read -r cx cy cz <<<"$($rough cells "$n")"
    "$bin/dynamod" -m 0 -x "$cx" -y "$cy" -z "$cz" -d "$density" --f1 "$alpha" \
        --f2="$(python3 -c "print(-$beta + 0.0)")" -s "$seed" -o "$d/config.lattice.xml" \
        > "$d/dynamod.log" 2>&1
    $rough prepare "$d/config.lattice.xml" "$d/seg.0.config.xml" --alpha "$alpha" \
        --beta "$beta" --seed "$seed" --temperature 1.0 --rotational-temperature "$trot"
}

case "$mode" in
hcs)
    particles=${1:-4000}
    phi=${2:-0.02}
    cpp=${3:-40}
    seeds=${4:-1,2,3}
    cases=${5:-"0.9:0.0 0.9:0.5 0.7:0.0 0.7:0.5"}
    trot_arg=${6:-0.0}
    IFS=, read -r -a seed_list <<<"$seeds"
    per=$(( particles / 2 ))   # collisions per segment: one per particle
    for c in $cases; do
        alpha=${c%%:*}
        beta=${c##*:}
        if [ "$trot_arg" = theory ]; then
            trot=$($rough theory --alpha "$alpha" --beta "$beta" | python3 -c "import json, sys; print(repr(json.load(sys.stdin)['ratio']))")
        else
            trot=$(python3 -c "print(repr(float($trot_arg)))")
        fi
        cdir=$out/a${alpha}_b${beta}
        mkdir -p "$cdir"
        echo "{\"alpha\": $alpha, \"beta\": $beta, \"particles\": $particles, \"packing_fraction\": $phi, \"collisions_per_particle\": $cpp, \"rotational_temperature\": $trot}" > "$cdir/case.json"
        for seed in "${seed_list[@]}"; do
            o=$cdir/seed.$seed
            d=$o/dynamo
            mkdir -p "$d"
            dynamo_start "$d" "$particles" "$phi" "$seed" "$alpha" "$beta" "$trot"
            start=$(date +%s.%N)
            for k in $(seq "$cpp"); do
                "$bin/dynarun" "$d/seg.$((k - 1)).config.xml" -c "$per" -o "$d/seg.$k.config.xml" \
                    --out-data-file "$d/seg.$k.output.xml" > "$d/seg.$k.log" 2>&1
            done
            end=$(date +%s.%N)
            $rough analyse "$d" --segments "$cpp"
            haff_toml "$o/haff.toml" "$particles" "$phi" "$seed" "$alpha" "$beta" "$cpp" $(( cpp + 1 )) "$trot"
            "$haff" run "$o/haff.toml" --out "$o/haff" --force > "$o/haff.log" 2>&1
            echo "alpha $alpha beta $beta seed $seed: DynamO $(python3 -c "print(round($end - $start, 1))") s;" \
                "dynamo $($rough summary "$d/timeseries.csv") haff $($rough summary "$o/haff/timeseries.csv")"
        done
    done
    echo "N = $particles, phi = $phi, $cpp collisions per particle, seeds $seeds, start T_rot = $trot_arg; T_rot/T_tr and -d ln T_tr / d(cpp) over 20..40:"
    $rough table "$out" | tee "$out/table.md"
    ;;
speed)
    particles=${1:-20000}
    phi=${2:-0.02}
    alpha=${3:-0.9}
    beta=${4:-0.5}
    cpp=${5:-20}
    repeats=${6:-3}
    core=${7:-1}
    cd "$out"
    total=$(python3 -c "print(round($cpp * $particles / 2))")
    dynamo_start "$out" "$particles" "$phi" 1 "$alpha" "$beta"
    haff_toml haff.toml "$particles" "$phi" 1 "$alpha" "$beta" "$cpp" 20
    now() { date +%s.%N; }
    rows=()
    echo "load before: $(uptime)"
    for r in $(seq "$repeats"); do
        t0=$(now)
        /usr/bin/time -f "%U %S" -o cpu.misc taskset -c "$core" "$bin/dynarun" seg.0.config.xml \
            -c "$total" -o end.xml --out-data-file out.xml > misc.log 2>&1
        t1=$(now)
        /usr/bin/time -f "%U %S" -o cpu.bare taskset -c "$core" "$bin/dynarun" seg.0.config.xml \
            -c "$total" -E -o end.E.xml > bare.log 2>&1
        t2=$(now)
        /usr/bin/time -f "%U %S" -o cpu.haff taskset -c "$core" "$haff" run haff.toml --out haff \
            --force > haff.log 2>&1
        t3=$(now)
        row=$(python3 - "$t0" "$t1" "$t2" "$t3" <<PY
import json, sys, xml.etree.ElementTree as ET
t0, t1, t2, t3 = map(float, sys.argv[1:])
misc = ET.parse("out.xml").getroot().find("Misc")
coll = sum(int(e.get("Count")) for e in misc.iter("Entry")
           if e.get("Type") == "Interaction" and e.get("Event") == "CORE")
loop = float(misc.find("Timing").get("EventsPerSec"))
h = json.load(open("haff/summary.json"))
cpu = {k: sum(map(float, open(f"cpu.{k}").read().split()[-2:])) for k in ("misc", "bare", "haff")}
print(json.dumps({"dynamo_cpu": cpu["misc"], "dynamo_cps_cpu": coll / cpu["misc"],
                  "dynamo_E_cpu": cpu["bare"], "dynamo_E_cps_cpu": $total / cpu["bare"],
                  "haff_cpu": cpu["haff"], "haff_cps_cpu": h["collisions"] / cpu["haff"],"dynamo_wall": t1 - t0, "dynamo_cps_wall": coll / (t1 - t0),
                  "dynamo_cps_loop": loop, "dynamo_E_wall": t2 - t1,
                  "dynamo_E_cps_wall": $total / (t2 - t1), "haff_wall": t3 - t2,
                  "haff_cps_wall": h["collisions"] / (t3 - t2),
                  "haff_cps": h["collisions_per_second"], "haff_eps": h["events_per_second"],
                  "haff_events_per_collision": h["events"] / h["collisions"],
                  "collisions": coll, "haff_collisions": h["collisions"]}))
PY
)
        rows+=("$row")
        echo "repeat $r: $row"
        echo "load: $(uptime)"
    done
    python3 - "${rows[@]}" <<PY | tee speed.txt
import json, statistics, sys
rows = [json.loads(x) for x in sys.argv[1:]]
med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
print(f"N = $particles, phi = $phi, alpha = $alpha, beta = $beta, {med['collisions']:.0f} collisions (DynamO), {med['haff_collisions']:.0f} (haff), core $core, medians of $repeats:")
print(f"  DynamO (Misc on):  {med['dynamo_wall']:.2f} s wall, {med['dynamo_cps_wall']:.3e} collisions/s (wall), {med['dynamo_cps_loop']:.3e} (Misc EventsPerSec)")
print(f"  DynamO -E:         {med['dynamo_E_wall']:.2f} s wall, {med['dynamo_E_cps_wall']:.3e} collisions/s (wall)")
print(f"  haff run:          {med['haff_wall']:.2f} s wall, {med['haff_cps_wall']:.3e} collisions/s (wall), {med['haff_cps']:.3e} (summary), {med['haff_eps']:.3e} events/s, {med['haff_events_per_collision']:.1f} events/collision")
print(f"  ratio haff/DynamO, collisions per wall second: {med['haff_cps_wall'] / med['dynamo_cps_wall']:.2f} (Misc on), {med['haff_cps_wall'] / med['dynamo_E_cps_wall']:.2f} (-E)")
print(f"  per CPU second (user + sys): DynamO {med['dynamo_cps_cpu']:.3e}, DynamO -E {med['dynamo_E_cps_cpu']:.3e}, haff {med['haff_cps_cpu']:.3e}; ratio {med['haff_cps_cpu'] / med['dynamo_cps_cpu']:.2f} (Misc on), {med['haff_cps_cpu'] / med['dynamo_E_cps_cpu']:.2f} (-E)")
print("JSON " + json.dumps(med))
PY
    ;;
*) echo "$usage" >&2; exit 2 ;;
esac
