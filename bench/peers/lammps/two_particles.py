#!/usr/bin/env python3
"""Head-on collision of two equal viscoelastic spheres in LAMMPS against `haff cor eps`.

    bench/peers/lammps/two_particles.py [--material soda-lime-glass] [--radius 1e-3]
        [--dissipative-constant 1e-9] [--v 0.01,0.1,1,10] [--divisions 100,200,400,800]
        [--naive] [--phases 4 | --phases 1 --phase 0.5] [--lmp lmp]
        [--haff target/release/haff] [--keep DIR]

LAMMPS `pair_style granular` with `hertz/material Y eta_n0 nu`, `damping viscoelastic`
and `limit_damping` is Eq. (2) of Mueller & Poeschel (2011) when

    eta_n0 = A Y / ((1 - nu^2) m_eff)        (derivation: README.md next to this file)

For every impact speed v the spheres approach head-on at relative speed v, the run
continues until they have separated, and eps = |v_rel after| / v is compared with
`haff cor eps --law exact` (`--naive`: LAMMPS without `limit_damping` against
`--law exact-naive`). The time step is t_H / D for every D of --divisions, t_H =
2.87 (m_eff^2 / (R_eff E_eff^2 v))^(1/5) the Hertz contact time at that v. The free flight
before the contact is a whole number of steps plus a fraction (the phase) of a step; the
phase fixes where inside a step the contact starts, the same for every time step. The
LAMMPS eps is the mean over --phases phases (k + 1/2)/N; their spread (max - min) is the
error of the contact start and end falling inside a step. The orders are those of the
last two time steps; "Richardson" is 2 eps(dt) - eps(2 dt) at the two smallest time steps
(first-order extrapolation). Prints a Markdown table.

Python 3 standard library + numpy only. Writes the LAMMPS inputs to a temporary directory.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))

# Y (Pa), nu, density (kg/m^3): crates/restitution/src/material.rs (TABLE); checked
# against `haff cor eps --format json` (beta) below.
MATERIALS = {
    "steel": (200e9, 0.30, 7850.0),
    "soda-lime-glass": (72e9, 0.23, 2500.0),
    "aluminium": (70e9, 0.33, 2700.0),
    "ice": (9.3e9, 0.33, 917.0),
}


def contact(young, poisson, density, radius, a_const):
    """Pair constants of two equal spheres (SI)."""
    mass = 4.0 / 3.0 * math.pi * radius**3 * density
    m_eff = mass / 2.0
    r_eff = radius / 2.0
    e_eff = young / (2.0 * (1.0 - poisson**2))  # LAMMPS mix_stiffnessE(Y, Y, nu, nu)
    rho = 2.0 * young * math.sqrt(r_eff) / (3.0 * (1.0 - poisson**2))  # Eq. (3)
    eta_n0 = a_const * young / ((1.0 - poisson**2) * m_eff)
    beta = 1.5 * a_const * (rho / m_eff) ** 0.4  # Eq. (8)
    return dict(mass=mass, m_eff=m_eff, r_eff=r_eff, e_eff=e_eff, rho=rho,
                eta_n0=eta_n0, beta=beta)


def hertz_time(c, v):
    return 2.87 * (c["m_eff"] ** 2 / (c["r_eff"] * c["e_eff"] ** 2 * v)) ** 0.2


LAMMPS_INPUT = """\
# two equal spheres, head-on, relative speed {v} m/s, dt = {dt:.17g} s (t_H/{div})
units           si
dimension       3
atom_style      sphere
boundary        f f f
atom_modify     map array
comm_modify     vel yes
region          box block {lo:.17g} {hi:.17g} {lo:.17g} {hi:.17g} {lo:.17g} {hi:.17g}
create_box      1 box
create_atoms    1 single {x1:.17g} 0 0
create_atoms    1 single {x2:.17g} 0 0
set             atom * diameter {diameter:.17g}
set             atom * density {density:.17g}
velocity        all set 0 0 0
set             atom 1 vx {half:.17g}
set             atom 2 vx {mhalf:.17g}
pair_style      granular
pair_coeff      * * hertz/material {young:.17g} {eta:.17g} {poisson:.17g} &
                tangential linear_nohistory 0.0 0.0 damping viscoelastic{limit}
neighbor        {skin:.17g} bin
neigh_modify    every 1 delay 0 check yes
fix             1 all nve/sphere
timestep        {dt:.17g}
thermo          0
run             {steps}
print           "RESULT $(vx[2]-vx[1]:%.17g) $(x[2]-x[1]:%.17g) $(mass[1]:%.17g)"
"""


def run_lammps(lmp, workdir, c, args, v, div, young, poisson, density, naive, phase):
    t_h = hertz_time(c, v)
    dt = t_h / div
    radius = args.radius
    # free flight: 5 whole steps + phase, then the contact and 2.5 t_H more
    gap = v * dt * (5 + phase)
    steps = 5 + int(math.ceil(2.5 * t_h / dt)) + 2
    text = LAMMPS_INPUT.format(
        v=v, dt=dt, div=div, lo=-20 * radius, hi=20 * radius,
        x1=-(radius + gap / 2), x2=radius + gap / 2, diameter=2 * radius,
        density=density, half=v / 2, mhalf=-v / 2, young=young, poisson=poisson,
        eta=c["eta_n0"], limit="" if naive else " limit_damping", skin=radius,
        steps=steps)
    path = os.path.join(workdir, f"in.two.v{v:g}.d{div}.p{phase:g}{'.naive' if naive else ''}")
    with open(path, "w") as f:
        f.write(text)
    out = subprocess.run([lmp, "-in", path, "-log", "none", "-echo", "none", "-nocite"],
                         capture_output=True, text=True, check=True,
                         env=dict(os.environ, OMP_NUM_THREADS="1")).stdout
    line = [l for l in out.splitlines() if l.startswith("RESULT")][-1].split()
    vrel, dist, mass = float(line[1]), float(line[2]), float(line[3])
    if dist <= 2 * radius:
        raise SystemExit(f"v = {v}, dt = t_H/{div}: the spheres have not separated")
    if abs(mass - c["mass"]) > 1e-12 * c["mass"]:
        raise SystemExit(f"LAMMPS mass {mass} differs from {c['mass']}")
    return vrel / v


def haff_eps(haff, args, speeds, naive):
    if args.dissipative_constant == 0.0:  # elastic: haff refuses beta = 0
        return 0.0, [1.0] * len(speeds)
    cmd = [haff, "cor", "eps", "--law", "exact-naive" if naive else "exact",
           "--v", ",".join(f"{v:g}" for v in speeds), "--material", args.material,
           "--radius", f"{args.radius:g}", "--dissipative-constant",
           f"{args.dissipative_constant:g}", "--format", "json"]
    data = json.loads(subprocess.run(cmd, capture_output=True, text=True,
                                     check=True).stdout)
    return data["beta"], [row["eps"] for row in data["rows"]]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--material", default="soda-lime-glass", choices=sorted(MATERIALS))
    p.add_argument("--radius", type=float, default=1e-3)
    p.add_argument("--dissipative-constant", type=float, default=1e-9)
    p.add_argument("--v", default="0.01,0.1,1,10")
    p.add_argument("--divisions", default="100,200,400,800",
                   help="time steps t_H/D, D comma-separated (halving: 100,200,400)")
    p.add_argument("--phase", type=float, default=0.5,
                   help="fraction of a step in the free flight before the contact")
    p.add_argument("--phases", type=int, default=4,
                   help="average over this many phases (k + 1/2)/N (1: --phase only)")
    p.add_argument("--naive", action="store_true",
                   help="no limit_damping in LAMMPS, --law exact-naive in haff")
    p.add_argument("--lmp", default="lmp")
    p.add_argument("--haff", default=os.path.join(ROOT, "target", "release", "haff"))
    p.add_argument("--keep", help="write the LAMMPS inputs to this directory")
    args = p.parse_args()

    young, poisson, density = MATERIALS[args.material]
    c = contact(young, poisson, density, args.radius, args.dissipative_constant)
    speeds = [float(s) for s in args.v.split(",")]
    divs = [int(s) for s in args.divisions.split(",")]
    beta, exact = haff_eps(args.haff, args, speeds, args.naive)
    if abs(beta - c["beta"]) > 1e-12 * beta or (beta == 0.0) != (c["beta"] == 0.0):
        raise SystemExit(f"beta: haff {beta} vs here {c['beta']} (material table?)")

    print(f"# {args.material}: Y = {young:g} Pa, nu = {poisson}, density = {density:g} "
          f"kg/m^3, R = {args.radius:g} m, A = {args.dissipative_constant:g} s")
    print(f"# m_eff = {c['m_eff']:.6g} kg, R_eff = {c['r_eff']:g} m, "
          f"E_eff = {c['e_eff']:.6g} Pa, rho = {c['rho']:.6g} Pa m^0.5, "
          f"beta = {beta:.6g} (s/m)^(1/5)")
    print(f"# eta_n0 = A Y / ((1 - nu^2) m_eff) = {c['eta_n0']:.10g} 1/(m s); "
          f"{'no limit_damping, haff exact-naive' if args.naive else 'limit_damping, haff exact'}")
    phases = [(k + 0.5) / args.phases for k in range(args.phases)] if args.phases > 1 \
        else [args.phase]
    print(f"# contact starts at phase(s) {', '.join(f'{x:g}' for x in phases)} of a step; "
          "LAMMPS eps = mean over the phases, spread = max - min over them")
    print("| v (m/s) | t_H (s) | eps haff | " +
          " | ".join(f"LAMMPS t_H/{d}" for d in divs) + " | " +
          " | ".join(f"diff t_H/{d}" for d in divs) + " | " +
          " | ".join(f"spread t_H/{d}" for d in divs) + " | order diff | order spread | Richardson - haff |")
    print("|" + "---|" * (6 + 3 * len(divs)))
    workdir = args.keep or tempfile.mkdtemp(prefix="lammps-two-")
    os.makedirs(workdir, exist_ok=True)
    for v, eps_h in zip(speeds, exact):
        runs = np.array([[run_lammps(args.lmp, workdir, c, args, v, d, young, poisson,
                                     density, args.naive, ph) for ph in phases]
                         for d in divs])
        eps = runs.mean(axis=1)
        spread = runs.max(axis=1) - runs.min(axis=1)
        diff = eps - eps_h
        # observed orders between the last two time steps: of the error against haff
        # (mean over the phases) and of the spread over the phases
        ratio = divs[-1] / divs[-2] if len(divs) >= 2 else float("nan")
        order = [math.log(abs(x[-2]) / abs(x[-1])) / math.log(ratio)
                 if len(divs) >= 2 and x[-1] != 0 and x[-2] != 0 else float("nan")
                 for x in (diff, spread)]
        row = [f"{v:g}", f"{hertz_time(c, v):.3g}", f"{eps_h:.10f}"] + \
            [f"{e:.10f}" for e in eps] + [f"{d:+.1e}" for d in diff] + \
            [f"{d:.1e}" for d in spread] + [f"{o:.1f}" for o in order] + \
            [f"{2 * eps[-1] - eps[-2] - eps_h:+.1e}" if len(divs) >= 2 else "nan"]
        print("| " + " | ".join(row) + " |", flush=True)
    if not args.keep:
        for name in os.listdir(workdir):
            os.remove(os.path.join(workdir, name))
        os.rmdir(workdir)


if __name__ == "__main__":
    sys.exit(main())
