#!/usr/bin/env bash
# Smallenburg's EDMD, Single variant (one event per particle, neighbour lists), side by side
# with `haff bench emd` on one core (bench/peers/edmd.sh Single ...).
#
#   bench/peers/edmd_single.sh EDMD_CHECKOUT [PARTICLES] [PACKING_FRACTION] [REPEATS] [CORE]
exec "$(dirname "$0")/edmd.sh" Single "$@"
