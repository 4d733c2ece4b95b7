#!/usr/bin/env python3
"""The same gas four ways in haff and once in LAMMPS: T(t) and wall time.

    bench/peers/lammps/three_ways.py RUN.toml [--seeds 4] [--haff target/release/haff]
        [--lmp lmp] [--out three_ways.csv] [--dt-factor 1] [--engines all]
        [--reference CSV] [--cpu 1]

RUN.toml is a haff run file (3D, one kind of sphere, `law = "viscoelastic"` with `young`,
`poisson`, `dissipative_constant`, `[run] engine = "soft-sphere"` with `end_time`, `samples`,
`spacing`), e.g. gas_three_ways.toml. From it, modified copies in a temporary directory run

* `soft-sphere`: haff's soft-sphere MD (its time step times --dt-factor),
* `emd-exact`, `emd-fast`: event-driven MD with `form = "exact"` and `"fast"`,
* `dsmc`: homogeneous DSMC (default scheme) with `form = "exact"`,
* `lammps`: gas_input.py (LAMMPS, `pair_style granular`, README.md) with haff's soft-sphere
  time step (`haff bench soft-sphere RUN --steps 10 --repeats 1 --format json`, key
  `time_step`) times --dt-factor and a skin of 0.3 diameters, T sampled ~4000 times and
  interpolated linearly onto haff's sample times,

each for the seeds 1..K (`system.seed`; gas_input.py places its own spheres from the same
seed, so only haff's eMD and soft-sphere runs share their initial state). Seeds are the
outer loop, engines the inner one, so that drifts of the machine hit every engine alike.
Every run is one process pinned to one core (`taskset -c CPU`); its wall clock is the whole
process (haff: set-up and output files included; LAMMPS: gas_input.py writing the data
file and lmp).

Writes the long CSV `engine,seed,time,temperature` and prints Markdown tables: at several
sample times the seed-mean T of each engine over the seed-mean T of eMD exact, +- the
standard error of the ratio (the two standard errors of the means over seeds propagated as
independent), and the seed mean of the per-seed ratio +- its standard error ("paired":
much smaller where the runs share their initial state and have not yet decorrelated); the
final T/T0, and the median wall time per engine with the ratios to eMD fast. With
--reference CSV (an earlier output, e.g. at --dt-factor 1), also the per-seed ratio of each
engine's T to its T there (a time-step convergence check with --dt-factor 0.5
--engines soft-sphere,lammps). Python >= 3.11 (tomllib) + numpy.
"""

import argparse
import json
import math
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ENGINES = ["emd-fast", "emd-exact", "soft-sphere", "lammps", "dsmc"]
SOFT_KEYS = ("steps_per_contact", "time_step")
DSMC_KEYS = ("dsmc_scheme", "block_size", "collisions_per_step", "collision_cell_width",
             "particle_weight")


def pinned(cpu, cmd):
    return (["taskset", "-c", str(cpu)] if shutil.which("taskset") else []) + cmd


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + " }"
    raise SystemExit(f"cannot write {v!r} as TOML")


def write_run(run, path):
    with open(path, "w") as f:
        for table in ("system", "collision", "run"):
            f.write(f"[{table}]\n")
            for key, value in run[table].items():
                f.write(f"{key} = {toml_value(value)}\n")


def variant(base, engine, seed, time_step):
    """The run file of one engine and seed (no [output]: no observers of space)."""
    run = {t: dict(base.get(t, {})) for t in ("system", "collision", "run")}
    run["system"]["seed"] = seed
    for key in DSMC_KEYS + SOFT_KEYS:
        run["run"].pop(key, None)
    if engine == "soft-sphere":
        run["run"]["engine"] = "soft-sphere"
        run["run"]["time_step"] = time_step
        run["collision"].pop("form", None)
    else:
        run["run"]["engine"] = "dsmc" if engine == "dsmc" else "event-driven"
        run["collision"]["form"] = "fast" if engine == "emd-fast" else "exact"
    return run


def timed(cmd):
    start = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.stderr.write(proc.stdout[-3000:] + proc.stderr[-3000:])
        raise SystemExit(f"{' '.join(cmd)} failed with status {proc.returncode}")
    return wall


def read_series(path):
    data = np.genfromtxt(path, delimiter=",", names=True)
    return np.atleast_1d(data["time"]), np.atleast_1d(data["temperature"])


def run_haff(args, work, run, name):
    path, out = work / f"{name}.toml", work / name
    write_run(run, path)
    wall = timed(pinned(args.cpu, [args.haff, "run", str(path), "--out", str(out), "--force"]))
    times, temps = read_series(out / "timeseries.csv")
    shutil.rmtree(out)
    return times, temps, wall


def run_lammps(args, work, run, name, dt, end):
    path, out = work / f"{name}.toml", work / f"{name}.csv"
    write_run(run, path)
    every = max(1, math.ceil(end / dt) // 4000)
    steps = every * math.ceil(end / (dt * every))
    wall = timed(pinned(args.cpu, [
        sys.executable, str(HERE / "gas_input.py"), str(path), "--steps", str(steps),
        "--thermo-every", str(every), "--dt", repr(dt), "--skin", "0.3", "--lmp", args.lmp,
        "--out", str(out)]))
    times, temps = read_series(out)
    return times, temps, wall


def read_long(path):
    """engine -> per-seed T rows (in seed order) of a CSV written by this script."""
    rows = {}
    with open(path) as f:
        next(f)
        for line in f:
            engine, seed, _t, temp = line.strip().split(",")
            rows.setdefault(engine, {}).setdefault(int(seed), []).append(float(temp))
    return {e: [by_seed[s] for s in sorted(by_seed)] for e, by_seed in rows.items()}


def mean_se(rows):
    """Mean over seeds (axis 0) and its standard error."""
    rows = np.asarray(rows)
    se = rows.std(axis=0, ddof=1) / math.sqrt(len(rows)) if len(rows) > 1 else \
        np.full(rows.shape[1:], math.nan)
    return rows.mean(axis=0), se


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="haff run file (TOML), engine soft-sphere with end_time")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--haff", default=str(HERE.parents[2] / "target" / "release" / "haff"))
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--out", default="three_ways.csv", help="long CSV engine,seed,time,T")
    ap.add_argument("--dt-factor", type=float, default=1.0,
                    help="multiplies the soft-sphere time step of haff and LAMMPS")
    ap.add_argument("--engines", default="all",
                    help="comma-separated subset of " + ",".join(ENGINES) +
                         " (emd-exact, the reference, always runs)")
    ap.add_argument("--reference", help="a CSV of this script (same run file and seeds): "
                    "also print T / T(reference) per engine, paired by seed")
    ap.add_argument("--cpu", type=int, default=1, help="core for taskset -c")
    args = ap.parse_args()
    engines = ENGINES if args.engines == "all" else \
        [e for e in ENGINES if e in args.engines.split(",") or e == "emd-exact"]
    if args.engines != "all" and set(args.engines.split(",")) - set(ENGINES):
        raise SystemExit(f"--engines: choose from {','.join(ENGINES)}")

    with open(args.run, "rb") as f:
        base = tomllib.load(f)
    end = base.get("run", {}).get("end_time")
    if end is None:
        raise SystemExit("run.end_time: missing (the engines must sample the same times)")
    bench = json.loads(subprocess.run(
        pinned(args.cpu, [args.haff, "bench", "soft-sphere", args.run, "--steps", "10",
                          "--repeats", "1", "--format", "json"]),
        check=True, capture_output=True, text=True).stdout)
    dt = bench["time_step"] * args.dt_factor
    t0 = float(base["system"]["temperature"])
    print(f"N = {bench['particles']}, phi = {bench['packing_fraction']}, end_time = {end}, "
          f"soft-sphere time step {bench['time_step']:.6g} x {args.dt_factor} = {dt:.6g}, "
          f"{args.seeds} seeds, engines {', '.join(engines)}", flush=True)

    temps = {e: [] for e in engines}
    walls = {e: [] for e in engines}
    times = None
    with tempfile.TemporaryDirectory(prefix="haff-three-ways-") as tmp:
        work = Path(tmp)
        for seed in range(1, args.seeds + 1):
            for engine in sorted(engines, key=lambda e: e == "lammps"):  # haff first
                run = variant(base, engine, seed, dt)
                name = f"{engine}-{seed}"
                if engine == "lammps":
                    t, temp, wall = run_lammps(args, work, run, name, dt, end)
                    temp = np.interp(times, t, temp)
                else:
                    t, temp, wall = run_haff(args, work, run, name)
                    if times is None:
                        times = t
                    elif len(t) != len(times) or np.abs(t - times).max() > 1e-9 * end:
                        raise SystemExit(f"{name}: sample times differ from the first run's")
                temps[engine].append(temp)
                walls[engine].append(wall)
                print(f"seed {seed} {engine:12s} wall {wall:8.3f} s, T_end/T0 = "
                      f"{temp[-1] / t0:.5f}", flush=True)

    with open(args.out, "w") as f:
        f.write("engine,seed,time,temperature\n")
        for engine in engines:
            for seed, row in enumerate(temps[engine], 1):
                for t, temp in zip(times, row):
                    f.write(f"{engine},{seed},{t:.17g},{temp:.17g}\n")

    picks = sorted({int(i) for i in np.linspace(1, len(times) - 1, 7).round()})
    ref = np.asarray(temps["emd-exact"])
    others = [e for e in engines if e != "emd-exact"]
    print(f"\nT / T(eMD exact), {args.seeds} seeds, dt factor {args.dt_factor}. Cells: ratio of "
          "the seed means +- standard error (propagated) / seed mean of the per-seed ratio "
          "+- its standard error (paired):\n")
    print("| t | T/T0 eMD exact | " + " | ".join(others) + " |")
    print("|---" * (len(others) + 2) + "|")
    m_ref, se_ref = mean_se(ref)
    for i in picks:
        cells = []
        for e in others:
            (m, se), (p, p_se) = mean_se(temps[e]), mean_se(np.asarray(temps[e]) / ref)
            r = m[i] / m_ref[i]
            cells.append(f"{r:.4f} ± {r * math.hypot(se[i] / m[i], se_ref[i] / m_ref[i]):.4f}"
                         f" / {p[i]:.4f} ± {p_se[i]:.4f}")
        print(f"| {times[i]:.4g} | {m_ref[i] / t0:.5f} ± {se_ref[i] / t0:.5f} | "
              + " | ".join(cells) + " |")
    if args.reference:
        other = read_long(args.reference)
        print(f"\nT / T({args.reference}), same engine and seed, seed mean of the ratio +- "
              "standard error:\n")
        common = [e for e in engines if e in other]
        print("| t | " + " | ".join(common) + " |\n" + "|---" * (len(common) + 1) + "|")
        for i in picks:
            cells = []
            for e in common:
                k = min(len(temps[e]), len(other[e]))
                p, p_se = mean_se(np.asarray(temps[e][:k]) / np.asarray(other[e][:k]))
                cells.append(f"{p[i]:.4f} ± {p_se[i]:.4f}")
            print(f"| {times[i]:.4g} | " + " | ".join(cells) + " |")
    stats = {e: mean_se(temps[e]) for e in engines}
    print("\nFinal T/T0 (seed mean +- standard error) and wall time per run (median):\n")
    unit = "emd-fast" if "emd-fast" in engines else "emd-exact"
    print(f"| engine | T_end/T0 | median wall s | wall / {unit} |\n|---|---|---|---|")
    base_wall = statistics.median(walls[unit])
    for e in engines:
        m, se = stats[e]
        w = statistics.median(walls[e])
        print(f"| {e} | {m[-1] / t0:.5f} ± {se[-1] / t0:.5f} | {w:.3f} | "
              f"{w / base_wall:.1f} |")
    print("\nwall ratios " + " : ".join(engines) + " = " +
          " : ".join(f"{statistics.median(walls[e]) / base_wall:.3g}" for e in engines))
    print(f"\n{sum(len(r) for r in temps.values()) * len(times)} rows in {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
