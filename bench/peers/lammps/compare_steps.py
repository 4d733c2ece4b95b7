#!/usr/bin/env python3
"""Time steps per second per particle: haff's soft-sphere engine against LAMMPS on the same
gas (a haff run file), interleaved on one core.

    bench/peers/lammps/compare_steps.py RUN.toml [--steps 2000] [--repeats 5]
        [--haff target/release/haff] [--lmp lmp]

Each repeat runs `haff bench soft-sphere RUN.toml --steps S --repeats 1` (S timed steps after
S of warm-up) and then gas_input.py (LAMMPS, S steps, its "Loop time") with haff's time step
and neighbour skin (0.3 diameters), alternating, so that drifts of the machine hit both
alike; `taskset -c 0` pins both to one core when available. Prints the medians, the ratio
LAMMPS / haff (above 1: haff is faster) and every repeat.
"""

import argparse
import json
import re
import shutil
import statistics
import tempfile
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def pinned(cmd):
    return (["taskset", "-c", "0"] if shutil.which("taskset") else []) + cmd


def haff_ns(haff, run, steps):
    out = subprocess.run(
        pinned([haff, "bench", "soft-sphere", str(run), "--steps", str(steps), "--repeats", "1",
                "--format", "json"]),
        check=True, capture_output=True, text=True).stdout
    report = json.loads(out)
    return report["ns_per_particle_step"], report["time_step"], report["particles"]


def lammps_ns(lmp, run, steps, dt):
    out = subprocess.run(
        pinned([sys.executable, str(HERE / "gas_input.py"), str(run), "--steps", str(steps),
                "--thermo-every", str(steps), "--dt", repr(dt), "--skin", "0.3", "--lmp", lmp,
                "--out", str(Path(tempfile.gettempdir()) / "haff-compare-T.csv")]),
        check=True, capture_output=True, text=True).stdout
    loop = re.search(r"loop time (\S+) s for (\d+) steps", out)
    n = re.search(r"N = (\d+)", out)
    if not loop or not n:
        sys.exit(f"could not read LAMMPS's loop time from:\n{out}")
    return float(loop.group(1)) / (int(loop.group(2)) * int(n.group(1))) * 1e9


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--haff", default=str(HERE.parents[2] / "target" / "release" / "haff"))
    ap.add_argument("--lmp", default="lmp")
    args = ap.parse_args()
    haff_times, lammps_times = [], []
    for repeat in range(args.repeats):
        ns, dt, n = haff_ns(args.haff, args.run, args.steps)
        haff_times.append(ns)
        lammps_times.append(lammps_ns(args.lmp, args.run, args.steps, dt))
        print(f"repeat {repeat + 1}: haff {haff_times[-1]:.2f} ns, LAMMPS {lammps_times[-1]:.2f} ns "
              f"per particle per step (N = {n}, dt = {dt:.4g})", flush=True)
    h, l = statistics.median(haff_times), statistics.median(lammps_times)
    print(f"median: haff {h:.2f} ns, LAMMPS {l:.2f} ns per particle per step; "
          f"LAMMPS / haff = {l / h:.2f}")


if __name__ == "__main__":
    main()
