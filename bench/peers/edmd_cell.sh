#!/usr/bin/env bash
# Smallenburg's EDMD, Cell variant, side by side with `haff bench emd` on one core
# (bench/peers/edmd.sh Cell ...).
#
#   bench/peers/edmd_cell.sh EDMD_CHECKOUT [PARTICLES] [PACKING_FRACTION] [REPEATS] [CORE]
exec "$(dirname "$0")/edmd.sh" Cell "$@"
