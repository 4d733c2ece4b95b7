#!/usr/bin/env python3
"""A haff run file (3D, viscoelastic law) as a LAMMPS input; runs it and writes T(t).

    bench/peers/lammps/gas_input.py RUN.toml [--steps 10000] [--thermo-every 100]
        [--dt DT | --divisions 50] [--skin 0.5] [--out temperature.csv] [--lmp lmp]
        [--workdir DIR] [--no-run]

RUN.toml (keys of issue 17; other tables and keys are ignored):

    [system]
    dimension = 3
    particles = 1000
    packing_fraction = 0.05
    diameter = 2e-3            # m
    mass = 1.0471975511965977e-5   # kg
    temperature = 1.0471975511965977e-5   # J, T = m <v^2> / 3 as in haff
    seed = 1
    [collision]
    law = "viscoelastic"
    young = 72e9               # Pa
    poisson = 0.23
    dissipative_constant = 1e-9   # s

Units: any coherent set, the run file's (SI in gas_small.toml, sigma = m = T0 = 1 in
gas_three_ways.toml). The input says `units si`, in which LAMMPS's force and energy
conversion factors are 1, so reduced numbers pass through unchanged; only LAMMPS's own
`compute temp` divides by k_B = 1.38e-23 (printed in the log, not used). The default time
step and the number formats (%.17g) are scale-free. The messages name SI units (m, s, J):
read them as the run file's units.

The gas: N equal spheres in a periodic cube of side L = (N pi d^3 / (6 phi))^(1/3), random
non-overlapping positions (random sequential addition, seeded), Maxwellian velocities with
zero total momentum rescaled to exactly T = m sum v^2 / (3 N), no rotation. The contact is
Eq. (2) of Mueller & Poeschel (2011): `pair_style granular`, `hertz/material Y eta_n0 nu`,
`damping viscoelastic`, `limit_damping` with eta_n0 = A Y / ((1 - nu^2) m_eff),
m_eff = m/2 (README.md next to this file), frictionless (`tangential linear_nohistory 0 0`),
`fix nve/sphere`. Default time step: t_H / 50, t_H the Hertz contact time at the relative
speed 5 sqrt(2 T / m) (a relative speed above it has probability ~1e-5 per collision).

Writes in.gas and gas.data to --workdir (a temporary directory unless given, removed after
the run), runs `lmp` (serial, one MPI rank, OMP_NUM_THREADS=1), and writes the CSV
`time,temperature` (s, J; haff's T from the kinetic energy: T = 2 KE / (3 N)) every
--thermo-every steps. Prints LAMMPS's version, the loop time (LAMMPS "Loop time") and the
wall time of the lmp process, and the loop time per step per particle.

Python 3 standard library (tomllib: Python >= 3.11) + numpy only.
"""

import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib

import numpy as np


def read_run(path):
    with open(path, "rb") as f:
        run = tomllib.load(f)
    system, collision = run.get("system", {}), run.get("collision", {})
    if system.get("dimension", 3) != 3:
        raise SystemExit("system.dimension: only 3 is supported")
    if "species" in system:
        raise SystemExit("system.species: only one species (diameter, mass) is supported")
    if collision.get("law") != "viscoelastic":
        raise SystemExit('collision.law: must be "viscoelastic"')
    need = {"system": ["particles", "packing_fraction", "diameter", "mass", "temperature"],
            "collision": ["young", "poisson", "dissipative_constant"]}
    for table, keys in need.items():
        for key in keys:
            if key not in run.get(table, {}):
                raise SystemExit(f"{table}.{key}: missing")
    p = dict(
        n=int(system["particles"]), phi=float(system["packing_fraction"]),
        d=float(system["diameter"]), m=float(system["mass"]),
        T=float(system["temperature"]), seed=int(system.get("seed", 1)),
        young=float(collision["young"]), poisson=float(collision["poisson"]),
        A=float(collision["dissipative_constant"]))
    if p["n"] < 2 or not 0 < p["phi"] <= 0.3 or min(p["d"], p["m"], p["T"], p["young"]) <= 0 \
            or not -1 < p["poisson"] < 0.5 or p["A"] < 0:
        raise SystemExit("out of range: particles >= 2, 0 < packing_fraction <= 0.3 "
                         "(random placement), diameter, mass, temperature, young > 0, "
                         "-1 < poisson < 0.5, dissipative_constant >= 0")
    return p


def contact(p):
    r = p["d"] / 2
    m_eff, r_eff = p["m"] / 2, r / 2
    e_eff = p["young"] / (2 * (1 - p["poisson"] ** 2))
    eta_n0 = p["A"] * p["young"] / ((1 - p["poisson"] ** 2) * m_eff)
    return m_eff, r_eff, e_eff, eta_n0


def hertz_time(m_eff, r_eff, e_eff, v):
    return 2.87 * (m_eff ** 2 / (r_eff * e_eff ** 2 * v)) ** 0.2


def random_positions(n, side, d, rng):
    """Random sequential addition of n spheres of diameter d in a periodic cube (cells)."""
    cells = max(1, int(side // d))
    width = side / cells
    grid = {}
    pos = np.empty((n, 3))
    placed, tries = 0, 0
    while placed < n:
        tries += 1
        if tries > 1000 * n:
            raise SystemExit("random placement failed: packing fraction too high")
        x = rng.random(3) * side
        c = (x // width).astype(int) % cells
        ok = True
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get(((c[0] + dx) % cells, (c[1] + dy) % cells,
                                       (c[2] + dz) % cells), ()):
                        r = x - pos[j]
                        r -= side * np.round(r / side)
                        if r @ r < d * d:
                            ok = False
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if not ok:
                break
        if ok:
            pos[placed] = x
            grid.setdefault(tuple(c), []).append(placed)
            placed += 1
    return pos


def maxwellian(n, m, T, rng):
    v = rng.normal(0.0, math.sqrt(T / m), size=(n, 3))
    v -= v.mean(axis=0)
    v *= math.sqrt(T / (m * (v * v).sum() / (3 * n)))
    return v


LAMMPS_INPUT = """\
# {n} viscoelastic spheres, phi = {phi}, from {source}
units           si
dimension       3
atom_style      sphere
boundary        p p p
comm_modify     vel yes
read_data       gas.data
pair_style      granular
pair_coeff      * * hertz/material {young:.17g} {eta:.17g} {poisson:.17g} &
                tangential linear_nohistory 0.0 0.0 damping viscoelastic limit_damping
neighbor        {skin:.17g} bin
neigh_modify    every 1 delay 0 check yes
fix             nve all nve/sphere
compute         T all temp
compute         ke all ke
variable        Th equal 2.0*c_ke/(3.0*atoms)
fix             Tout all ave/time {every} 1 {every} v_Th c_T file temperature.txt format " %.17g"
timestep        {dt:.17g}
thermo_style    custom step time c_T v_Th
thermo          {thermo}
run             {steps}
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run", help="haff run file (TOML)")
    ap.add_argument("--steps", type=int, default=10000)
    ap.add_argument("--thermo-every", type=int, default=100)
    ap.add_argument("--dt", type=float, help="time step in s (default: t_H/DIVISIONS)")
    ap.add_argument("--divisions", type=float, default=50.0)
    ap.add_argument("--skin", type=float, default=0.5, help="neighbor skin in diameters")
    ap.add_argument("--out", default="temperature.csv", help="CSV time,temperature")
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--workdir", help="keep in.gas, gas.data, log.lammps here")
    ap.add_argument("--no-run", action="store_true", help="write the input only")
    args = ap.parse_args()

    p = read_run(args.run)
    m_eff, r_eff, e_eff, eta_n0 = contact(p)
    side = (p["n"] * math.pi * p["d"] ** 3 / (6 * p["phi"])) ** (1 / 3)
    v_ref = 5 * math.sqrt(2 * p["T"] / p["m"])
    t_h = hertz_time(m_eff, r_eff, e_eff, v_ref)
    dt = args.dt if args.dt else t_h / args.divisions

    rng = np.random.default_rng(p["seed"])
    pos = random_positions(p["n"], side, p["d"], rng)
    vel = maxwellian(p["n"], p["m"], p["T"], rng)
    density = p["m"] / (math.pi / 6 * p["d"] ** 3)

    workdir = args.workdir or tempfile.mkdtemp(prefix="lammps-gas-")
    os.makedirs(workdir, exist_ok=True)
    with open(os.path.join(workdir, "gas.data"), "w") as f:
        f.write(f"# {p['n']} spheres from {os.path.basename(args.run)}\n\n"
                f"{p['n']} atoms\n1 atom types\n\n"
                f"0 {side:.17g} xlo xhi\n0 {side:.17g} ylo yhi\n0 {side:.17g} zlo zhi\n\n"
                "Atoms # sphere\n\n")
        for i, x in enumerate(pos, 1):
            f.write(f"{i} 1 {p['d']:.17g} {density:.17g} {x[0]:.17g} {x[1]:.17g} "
                    f"{x[2]:.17g}\n")
        f.write("\nVelocities\n\n")
        for i, v in enumerate(vel, 1):
            f.write(f"{i} {v[0]:.17g} {v[1]:.17g} {v[2]:.17g} 0 0 0\n")
    with open(os.path.join(workdir, "in.gas"), "w") as f:
        f.write(LAMMPS_INPUT.format(
            n=p["n"], phi=p["phi"], source=os.path.basename(args.run), young=p["young"],
            eta=eta_n0, poisson=p["poisson"], skin=args.skin * p["d"],
            every=args.thermo_every, dt=dt, thermo=max(args.steps // 10, 1),
            steps=args.steps))
    print(f"N = {p['n']}, phi = {p['phi']}, L = {side:.6g} m, eta_n0 = {eta_n0:.10g} 1/(m s)")
    print(f"dt = {dt:.6g} s = t_H/{t_h / dt:.3g} (t_H = {t_h:.4g} s at v = {v_ref:.4g} m/s)")
    if args.no_run:
        print(f"input in {workdir}")
        return 0

    start = time.perf_counter()
    proc = subprocess.run([args.lmp, "-in", "in.gas", "-nocite"], cwd=workdir,
                          capture_output=True, text=True,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.stderr.write(proc.stdout[-3000:] + proc.stderr[-3000:])
        raise SystemExit(f"lmp failed with status {proc.returncode}")
    version = re.search(r"LAMMPS \((.*?)\)", proc.stdout)
    loop = re.search(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                     proc.stdout)
    rows = []
    with open(os.path.join(workdir, "temperature.txt")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            step, t_haff, _t_lammps = line.split()
            rows.append((int(step) * dt, float(t_haff)))
    with open(args.out, "w") as f:
        f.write("time,temperature\n")
        for t, temp in rows:
            f.write(f"{t:.17g},{temp:.17g}\n")
    loop_time, steps, atoms = float(loop.group(1)), int(loop.group(3)), int(loop.group(4))
    print(f"LAMMPS {version.group(1) if version else '?'}, {loop.group(2)} proc(s)")
    print(f"wall time {wall:.3f} s (lmp process), loop time {loop_time:.3f} s for {steps} "
          f"steps with {atoms} atoms: {loop_time / (steps * atoms) * 1e9:.1f} ns per step "
          f"per particle")
    print(f"T: {rows[0][1]:.6g} J at t = 0 -> {rows[-1][1]:.6g} J at t = {rows[-1][0]:.6g} s;"
          f" {len(rows)} rows in {args.out}")
    if not args.workdir:
        shutil.rmtree(workdir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
