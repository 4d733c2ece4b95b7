#!/usr/bin/env bash
# Smallenburg's EDMD (Cell or Single variant) side by side with `haff bench emd` on one core.
#
#   bench/peers/edmd.sh VARIANT EDMD_CHECKOUT [PARTICLES] [PACKING_FRACTION] [REPEATS] [CORE]
#
# VARIANT is Cell (collision checks from cell lists) or Single (one event per
# particle, neighbour lists with a shell of 1.5 diameters; Smallenburg, EPJE 45, 22 (2022)).
# EDMD_CHECKOUT is a checkout of https://github.com/FSmallenburg/EDMD (its public source;
# nothing of it is copied into haff). The script copies VARIANT/ to a scratch directory, sets
# the run's parameters in its globals (N, packing fraction, FCC start, end time; Single's
# thermostat off: the gas is elastic and conserves its energy as haff's does), builds it
# with its own Makefile (gcc -Ofast -funroll-loops -march=native), and runs it and
# `haff bench emd` (elastic 3D gas, same N and phi) alternately, pinned to one core, REPEATS
# times each. It prints the collisions per second of each run, the medians and their ratio.
# Defaults: N = 108000 (EDMD's FCC start needs 4 k^3), phi = 0.05, 5 repeats, core 1.
set -euo pipefail
usage="usage: $0 Cell|Single EDMD_CHECKOUT [PARTICLES] [PACKING_FRACTION] [REPEATS] [CORE]"
variant=${1:?$usage}
checkout=${2:?$usage}
particles=${3:-108000}
phi=${4:-0.05}
repeats=${5:-5}
core=${6:-1}
case "$variant" in
    Cell) source_file=mdCell.c ;;
    Single) source_file=mdSingle.c ;;
    *) echo "$usage" >&2; exit 2 ;;
esac
root=$(cd "$(dirname "$0")/../.." && pwd)
haff=${HAFF_BIN:-$root/target/release/haff}
[ -x "$haff" ] || (cd "$root" && cargo build --release -p haff-cli)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp -r "$checkout/$variant" "$scratch/"
cd "$scratch/$variant"
# Simulated time for about 40 collisions per particle: the Enskog collision frequency at
# T = 1 (EDMD's start) is 4 sqrt(pi) n sigma^2 chi sqrt(T/m) per particle.
maxtime=$(python3 -c "
import math
phi = $phi
n = 6 * phi / math.pi
chi = (1 - phi / 2) / (1 - phi) ** 3
print(40 / (4 * math.sqrt(math.pi) * n * chi))")
sed -i -e "s/^double maxtime = .*/double maxtime = $maxtime;/" \
       -e "s/^double writeinterval = .*/double writeinterval = $maxtime;/" \
       -e "s/^int initialconfig = .*/int initialconfig = 1;/" \
       -e "s/^double packfrac = .*/double packfrac = $phi;/" \
       -e "s/^int N = .*/int N = $particles;/" \
       -e "s/^const int usethermostat = .*/const int usethermostat = 0;/" "$source_file"
make -s >/dev/null
events=$(python3 -c "print(int(40 * $particles / 2 * 7.5))")
edmd=() ours=()
for r in $(seq "$repeats"); do
    start=$(date +%s.%N)
    out=$(taskset -c "$core" ./md)
    end=$(date +%s.%N)
    collisions=$(echo "$out" | grep -o 'Collisions: [0-9]*' | tail -1 | awk '{print $2}')
    rate=$(python3 -c "print($collisions / ($end - $start))")
    edmd+=("$rate")
    json=$(taskset -c "$core" "$haff" bench emd --particles "$particles" \
        --packing-fraction "$phi" --events "$events" --repeats 1 --format json)
    ours+=("$(echo "$json" | python3 -c 'import json,sys; print(json.load(sys.stdin)["collisions_per_second"])')")
    echo "repeat $r: EDMD-$variant ${edmd[-1]} collisions/s (process, $collisions collisions), haff ${ours[-1]}"
done
python3 - "${edmd[*]}" "${ours[*]}" <<PY
import statistics, sys
edmd = [float(x) for x in sys.argv[1].split()]
ours = [float(x) for x in sys.argv[2].split()]
e, o = statistics.median(edmd), statistics.median(ours)
print(f"N = $particles, phi = $phi, core $core, medians of $repeats: EDMD-$variant {e:.3e}, haff {o:.3e} collisions/s, ratio haff/EDMD = {o / e:.2f}")
PY
