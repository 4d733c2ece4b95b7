#!/usr/bin/env python3
"""Weak and strong scaling of DSMC (spatial, or the homogeneous block scheme) from 1 to 2 MPI ranks, interleaved.

Runs `mpirun -n R haff run` (the binary built with `--features mpi`, one rayon thread per
rank, each rank bound to a core) on a freely cooling 3D gas, in rounds that take every
configuration once, and reports medians of the run time (summary.json `run_seconds`: the
run without building it) and, for 2 ranks, the per-rank communication (summary.json
`parallel`). Also 1 process on 2 threads, the alternative on one machine.

    cargo build --release --features mpi --target-dir target/mpi -p haff-cli
    bench/mpi/scaling.py --repeats 5
    bench/mpi/scaling.py --scheme blocks --repeats 5

Weak scaling: N per rank fixed (efficiency t(1 rank, n) / t(2 ranks, 2n)); strong: N
fixed (efficiency t(1 rank, N) / (2 t(2 ranks, N))).
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

GAS = """[system]
dimension = 3
particles = {particles}
packing_fraction = 0.05
seed = 3
[collision]
law = "constant"
restitution = 0.9
[run]
engine = "dsmc"
dsmc_scheme = "{scheme}"
collisions_per_particle = {collisions}
samples = 2
spacing = "linear"
"""


def run(binary, scheme, ranks, threads, particles, collisions, scratch):
    """One run; returns its summary.json."""
    file = scratch / f"gas_{particles}.toml"
    file.write_text(GAS.format(particles=particles, collisions=collisions, scheme=scheme))
    out = scratch / f"out_{ranks}_{threads}_{particles}"
    env = dict(
        os.environ,
        RAYON_NUM_THREADS=str(threads),
        OMPI_ALLOW_RUN_AS_ROOT="1",
        OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
        OMPI_MCA_btl="self,vader",
        OMPI_MCA_btl_vader_single_copy_mechanism="none",
    )
    bind = ["--bind-to", "core"] if threads == 1 else ["--bind-to", "none"]
    command = ["mpirun", "-n", str(ranks), *bind, str(binary), "run", str(file),
               "--out", str(out), "--force"]
    subprocess.run(command, env=env, check=True, capture_output=True)
    return json.loads((out / "summary.json").read_text())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--binary", default=ROOT / "target/mpi/release/haff", type=Path)
    parser.add_argument("--particles", type=int, default=1_000_000,
                        help="N of the strong-scaling runs (and per rank of the weak ones: N/2)")
    parser.add_argument("--collisions", type=float, default=20.0,
                        help="collisions per particle of every run")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--scheme", choices=["spatial", "blocks"], default="spatial",
                        help="dsmc_scheme: spatial (slabs of cells) or blocks (homogeneous)")
    args = parser.parse_args()
    n, half = args.particles, args.particles // 2
    configs = {
        "1 rank, N/2": (1, 1, half),
        "1 rank, N": (1, 1, n),
        "2 ranks, N": (2, 1, n),
        "1 rank x 2 threads, N": (1, 2, n),
    }
    times = {name: [] for name in configs}
    parallel = []
    with tempfile.TemporaryDirectory() as scratch:
        for _ in range(args.repeats):
            for name, (ranks, threads, particles) in configs.items():
                summary = run(args.binary, args.scheme, ranks, threads, particles,
                              args.collisions, Path(scratch))
                times[name].append(summary["run_seconds"])
                if ranks == 2:
                    parallel.append(summary["parallel"])
    median = {name: statistics.median(t) for name, t in times.items()}
    print(f"{args.scheme}: N = {n}, {args.collisions} collisions per particle, "
          f"medians of {args.repeats}")
    for name, t in median.items():
        spread = f"{min(times[name]):.3f} .. {max(times[name]):.3f}"
        print(f"  {name:24s} {t:8.3f} s  ({spread})")
    # Weak: 1 rank with N/2 against 2 ranks with N/2 each.
    print(f"weak-scaling efficiency 1 -> 2 ranks:   {median['1 rank, N/2'] / median['2 ranks, N']:.3f}")
    print(f"strong-scaling efficiency 1 -> 2 ranks: "
          f"{median['1 rank, N'] / (2 * median['2 ranks, N']):.3f}")
    print(f"2 threads in one process, efficiency:   "
          f"{median['1 rank, N'] / (2 * median['1 rank x 2 threads, N']):.3f}")
    p = parallel[len(parallel) // 2]
    steps = p["steps"]
    per_step = p["step_seconds"]
    print(f"2 ranks: {steps} steps of {per_step:.4e} s; per rank and step: "
          f"{p['bytes_sent_per_rank_per_step']:.0f} bytes migrating, "
          f"{p['reduction_bytes_per_rank_per_step']} bytes in all-reduces, "
          f"{p['communication_seconds_per_step']:.3e} s communicating "
          f"({100 * p['communication_fraction']:.1f} %), load imbalance {p['load_imbalance']:.4f}")
    for r in p["per_rank"]:
        print(f"  rank {r['rank']}: {r['particles']} particles, {r['cells']} {'blocks' if args.scheme == 'blocks' else 'cells'}, "
              f"{r['migrants_sent'] / steps:.0f} migrants and {r['bytes_sent'] / steps:.0f} "
              f"bytes sent per step, {r['communication_seconds'] / steps:.3e} s of "
              f"{r['step_seconds'] / steps:.3e} s per step communicating")


if __name__ == "__main__":
    main()
