"""Benchmarks of the Python package against the Rust code and numpy (issue: Python package).

    python python/benchmarks/bench.py [--haff target/release/haff] [--repeats 7]

1. haff.eps(x, "fast") on 1e7 log-spaced v* in [1e-3, 1e3]: ns per value, against the Rust
   fast law (`haff bench cor`, its median) and against numpy evaluating the Padé [3/6] of
   Müller & Pöschel 2011 (Horner, numerator and denominator) on the same array.
2. Simulation.run() against `haff run` on the same file (wall seconds, interleaved).

Every figure is the median of the repeats, the runs interleaved so that both sides see the
same machine state.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import haff

ROOT = Path(__file__).resolve().parents[2]


def median_seconds(call, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times), times


def numpy_pade(v, a, b):
    num = np.full_like(v, a[-1])
    for c in a[-2::-1]:
        num *= v
        num += c
    den = np.full_like(v, b[-1])
    for c in b[-2::-1]:
        den *= v
        den += c
    return num / den


def bench_eps(haff_bin, repeats):
    n = 10_000_000
    v = np.geomspace(1e-3, 1e3, n)
    a, b = haff.pade(3, 6)
    # The numpy Padé is the law pade:3/6 (checked, not assumed).
    sample = v[:: n // 1000]
    np.testing.assert_allclose(numpy_pade(sample, a, b), haff.eps(sample, "pade:3/6"), rtol=1e-12)
    ours, numpys = [], []
    for _ in range(repeats):  # interleaved
        ours.append(median_seconds(lambda: haff.eps(v, "fast"), 1)[0])
        numpys.append(median_seconds(lambda: numpy_pade(v, a, b), 1)[0])
    cor = subprocess.run([str(haff_bin), "bench", "cor", "--format", "json"], check=True,
                         capture_output=True, text=True).stdout
    rust = {row["law"]: row["median_ns"] for row in json.loads(cor)["results"]}
    ns_ours = statistics.median(ours) / n * 1e9
    ns_numpy = statistics.median(numpys) / n * 1e9
    print(f"haff.eps(fast), 1e7 values: {ns_ours:.2f} ns/value (median of {repeats}; "
          f"min {min(ours) / n * 1e9:.2f}, max {max(ours) / n * 1e9:.2f})")
    print(f"Rust fast law (haff bench cor): {rust['fast']:.2f} ns/value -> ratio "
          f"{ns_ours / rust['fast']:.2f} (target <= 1.5)")
    print(f"numpy Padé [3/6], 1e7 values: {ns_numpy:.2f} ns/value -> haff is "
          f"{ns_numpy / ns_ours:.1f}x faster (target >= 5)")


GAS = """[system]
particles = 20000
packing_fraction = 0.1
seed = 3
[collision]
law = "constant"
restitution = 0.9
[run]
collisions_per_particle = 100
samples = 21
"""


def bench_run(haff_bin, repeats):
    with tempfile.TemporaryDirectory() as tmp:
        file = Path(tmp) / "gas.toml"
        file.write_text(GAS)
        cli, py, cli_run, py_run = [], [], [], []
        for k in range(repeats):  # interleaved
            out = Path(tmp) / f"out{k}"
            start = time.perf_counter()
            subprocess.run([str(haff_bin), "run", str(file), "--out", str(out)], check=True,
                           capture_output=True)
            cli.append(time.perf_counter() - start)
            cli_run.append(json.loads((out / "summary.json").read_text())["wall_seconds"])
            start = time.perf_counter()
            sim = haff.Simulation(file)
            sim.run(progress=False)
            py_run.append(sim.wall_seconds)
            sim.write(Path(tmp) / f"py{k}")
            py.append(time.perf_counter() - start)
        c, p = statistics.median(cli), statistics.median(py)
        cr, pr = statistics.median(cli_run), statistics.median(py_run)
        print(f"haff run (N = 2e4, phi = 0.1, 100 collisions per particle), medians of "
              f"{repeats}: whole command {c:.3f} s, Simulation(file).run() + write {p:.3f} s "
              f"({100 * (p / c - 1):+.1f} %); building + running only (wall_seconds): "
              f"{cr:.3f} s vs {pr:.3f} s ({100 * (pr / cr - 1):+.1f} %; target <= +5 %)")
        print(f"  all runs, command: {', '.join(f'{x:.2f}' for x in cli_run)}")
        print(f"  all runs, Python:  {', '.join(f'{x:.2f}' for x in py_run)}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--haff", default=str(ROOT / "target" / "release" / "haff"))
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    bench_eps(args.haff, args.repeats)
    bench_run(args.haff, args.repeats)


if __name__ == "__main__":
    main()
