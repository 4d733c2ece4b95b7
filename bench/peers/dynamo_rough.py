#!/usr/bin/env python3
"""Helpers of bench/peers/dynamo_rough.sh: the homogeneous cooling state (HCS) of rough hard
spheres in DynamO and in haff, side by side (3D, constant normal restitution alpha,
constant tangential restitution beta, solid spheres q = 2/5).

    dynamo_rough.py cells N                       -> "X Y Z": FCC unit cells, 4 X Y Z = N
    dynamo_rough.py prepare IN OUT --alpha A --beta B --seed S [--temperature T]
                                   [--rotational-temperature TR]
    dynamo_rough.py analyse DIR --segments K      -> DIR/timeseries.csv (DynamO segments)
    dynamo_rough.py summary CSV [--first 20] [--last 40]   -> JSON: ratio, slope
    dynamo_rough.py theory --alpha A --beta B [--inertia 0.4]  -> JSON: ratio, slope
    dynamo_rough.py table OUTDIR                  -> markdown table of OUTDIR/*/seed.*/

Conventions. haff's beta: the contact points' tangential relative velocity g_t' = -beta g_t
(beta = -1 smooth, +1 perfectly rough). DynamO's HardSphere interaction with a
TangentialElasticity e_t (DynNewtonian::RoughSpheresColl, src/dynamo/dynamo/dynamics/
newtonian.cpp) gives g_t' = +e_t g_t, so e_t = -beta; its rule uses the moment of inertia
I = 2/5 m (d/2)^2 (hard-coded, `double I = 2.0 / 5.0;`) whatever the species says; the
species (SphericalTop, InertiaConstant = I / m) is set to the same 2/5 (d/2)^2 = 0.1 for
d = 1 so that the energies DynamO reports are those its collisions use.

`prepare` rewrites a configuration of `dynamod -m 0 --f1 ALPHA --f2=-BETA` (monocomponent
hard spheres; --f2 != 1 makes them rough: HardSphere with TangentialElasticity, a
SphericalTop species, orientation data): it checks/sets Elasticity, TangentialElasticity,
the species' InertiaConstant, and replaces the velocities (Gaussian, total momentum zero,
rescaled to T exactly) and the angular velocities (zero when TR = 0, else Gaussian rescaled
to I <w^2> / 3 = TR exactly). dynamod's own angular velocities (Dynamics::initOrientations:
perpendicular to a director, for its line molecules) are not used.

`analyse` reads DIR/seg.K.config.xml (the configuration after segment K; seg.0 is the start)
and DIR/seg.K.output.xml (the Misc output of segment K: its collision count and duration):
T_tr = sum m v^2 / (3 N), T_rot = sum I w^2 / (3 N), collisions per particle = 2 C / N
(haff's count), time = the summed segment durations.
"""
import argparse
import csv
import glob
import json
import math
import os
import random
import statistics
import sys
import xml.etree.ElementTree as ET

Q_SOLID = 0.4


def cells(n):
    if n % 4:
        sys.exit(f"N = {n} is not 4 X Y Z (FCC unit cells)")
    m = n // 4
    best = None
    for x in range(1, m + 1):
        if m % x:
            continue
        for y in range(1, m // x + 1):
            if (m // x) % y:
                continue
            z = m // x // y
            spread = max(x, y, z) / min(x, y, z)
            if best is None or spread < best[0]:
                best = (spread, x, y, z)
    print(best[1], best[2], best[3])


def the_species(root):
    sp = list(root.iter("Species"))
    if len(sp) != 1:
        sys.exit("expected one species")
    return sp[0]


def prepare(args):
    tree = ET.parse(args.input)
    root = tree.getroot()
    inters = [i for i in root.iter("Interaction") if i.get("Type") == "HardSphere"]
    if len(inters) != 1:
        sys.exit("expected one HardSphere interaction (dynamod -m 0)")
    inter = inters[0]
    if float(inter.get("Diameter")) != 1.0:
        sys.exit("expected Diameter 1 (dynamod's unit of length)")
    if inter.get("TangentialElasticity") is None:
        sys.exit("no TangentialElasticity: make the configuration with dynamod --f2 != 1")
    inter.set("Elasticity", repr(args.alpha))
    inter.set("TangentialElasticity", repr(-args.beta + 0.0))  # no "-0.0"
    sp = the_species(root)
    if sp.get("Type") != "SphericalTop":
        sys.exit(f"expected a SphericalTop species, got {sp.get('Type')}")
    if float(sp.get("Mass")) != 1.0:
        sys.exit("expected Mass 1")
    inertia = Q_SOLID * 0.25  # I / m = q (d/2)^2, d = 1
    sp.set("InertiaConstant", repr(inertia))
    pdata = root.find("ParticleData")
    if pdata.get("OrientationData") != "Y":
        sys.exit("no orientation data in the configuration")
    pts = list(pdata.iter("Pt"))
    n = len(pts)
    rng = random.Random(args.seed)

    def gaussian_set(temp, mass):
        vel = [[rng.gauss(0.0, 1.0) for _ in range(3)] for _ in range(n)]
        mean = [sum(v[c] for v in vel) / n for c in range(3)]
        vel = [[v[c] - mean[c] for c in range(3)] for v in vel]
        t = mass * sum(v[c] ** 2 for v in vel for c in range(3)) / (3 * n)
        scale = math.sqrt(temp / t)
        return [[x * scale for x in v] for v in vel]

    vel = gaussian_set(args.temperature, 1.0)
    if args.rotational_temperature > 0:
        omega = gaussian_set(args.rotational_temperature, inertia)
    else:
        omega = [[0.0, 0.0, 0.0] for _ in range(n)]
    for pt, v, w in zip(pts, vel, omega):
        for tag, vec in (("V", v), ("O", w)):
            node = pt.find(tag)
            for c, x in zip("xyz", vec):
                node.set(c, repr(x))
    tree.write(args.output, xml_declaration=True, encoding="utf-8")


def temperatures(path):
    root = ET.parse(path).getroot()
    sp = the_species(root)
    mass = float(sp.get("Mass"))
    inertia = float(sp.get("InertiaConstant")) * mass
    n = 0
    kin = rot = 0.0
    for pt in root.find("ParticleData").iter("Pt"):
        v, w = pt.find("V"), pt.find("O")
        kin += mass * sum(float(v.get(c)) ** 2 for c in "xyz")
        rot += inertia * sum(float(w.get(c)) ** 2 for c in "xyz")
        n += 1
    return n, kin / (3 * n), rot / (3 * n)


def misc(path):
    m = ET.parse(path).getroot().find("Misc")
    coll = sum(
        int(e.get("Count"))
        for e in m.iter("Entry")
        if e.get("Type") == "Interaction" and e.get("Event") == "CORE"
    )
    return coll, float(m.find("Duration").get("Time"))


def analyse(args):
    rows = []
    coll = 0
    time = 0.0
    for k in range(args.segments + 1):
        n, t_tr, t_rot = temperatures(f"{args.dir}/seg.{k}.config.xml")
        if k > 0:
            c, dt = misc(f"{args.dir}/seg.{k}.output.xml")
            coll += c
            time += dt
        rows.append((time, 2 * coll / n, t_tr, t_rot))
    with open(f"{args.dir}/timeseries.csv", "w") as f:
        f.write("time,collisions_per_particle,temperature,rotational_temperature\n")
        for r in rows:
            f.write(",".join(repr(x) for x in r) + "\n")


def summarise(path, first, last):
    with open(path) as f:
        rows = [
            r
            for r in csv.DictReader(f)
            if first <= float(r["collisions_per_particle"]) <= last
        ]
    cpp = [float(r["collisions_per_particle"]) for r in rows]
    t = [float(r["temperature"]) for r in rows]
    tr = [float(r["rotational_temperature"]) for r in rows]
    ratio = statistics.mean(b / a for a, b in zip(t, tr))
    y = [-math.log(a) for a in t]
    mx, my = statistics.mean(cpp), statistics.mean(y)
    slope = sum((x - mx) * (z - my) for x, z in zip(cpp, y)) / sum((x - mx) ** 2 for x in cpp)
    return {"ratio": ratio, "slope": slope, "samples": len(rows)}


def theory(alpha, beta, q=Q_SOLID):
    eta = q * (1 + beta) / (2 * (1 + q))
    a = (1 - alpha**2) / 4 + eta * (1 - eta)
    b = eta**2 / q
    c = (eta / q) * (1 - eta / q)
    if b == 0:
        return {"ratio": 0.0, "slope": 4 * a / 3}
    r = (-(c - a) + math.sqrt((c - a) ** 2 + 4 * b * b)) / (2 * b)
    # -d ln T_tr / d tau = (4 / 3)(A - B r), tau the collisions per particle (3D, c = 4)
    return {"ratio": r, "slope": 4 * (a - b * r) / 3}


def mean_se(xs):
    m = statistics.mean(xs)
    se = statistics.stdev(xs) / math.sqrt(len(xs)) if len(xs) > 1 else float("nan")
    return m, se


def table(args):
    lines = [
        "| alpha | beta (haff) | e_t (DynamO) | seeds | T_rot/T_tr DynamO | T_rot/T_tr haff | "
        "theory | diff/err | slope DynamO | slope haff | theory | diff/err |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    out = {}
    for case in sorted(glob.glob(f"{args.outdir}/a*_b*")):
        spec = json.load(open(f"{case}/case.json"))
        alpha, beta = spec["alpha"], spec["beta"]
        res = {"dynamo": [], "haff": []}
        for seed_dir in sorted(glob.glob(f"{case}/seed.*")):
            for code, csvp in (
                ("dynamo", f"{seed_dir}/dynamo/timeseries.csv"),
                ("haff", f"{seed_dir}/haff/timeseries.csv"),
            ):
                if os.path.exists(csvp):
                    res[code].append(summarise(csvp, args.first, args.last))
        if not res["dynamo"] or not res["haff"]:
            continue
        th = theory(alpha, beta)
        row = {"alpha": alpha, "beta": beta, "theory": th}
        cells_ = [f"{alpha}", f"{beta}", f"{-beta + 0.0}", f"{len(res['dynamo'])}/{len(res['haff'])}"]
        for key in ("ratio", "slope"):
            d = mean_se([r[key] for r in res["dynamo"]])
            h = mean_se([r[key] for r in res["haff"]])
            err = math.hypot(d[1], h[1])
            z = (d[0] - h[0]) / err if err > 0 else float("nan")
            row[key] = {"dynamo": d, "haff": h, "z": z}
            cells_ += [f"{d[0]:.4f} ± {d[1]:.4f}", f"{h[0]:.4f} ± {h[1]:.4f}", f"{th[key]:.4f}", f"{z:+.1f}"]
        lines.append("| " + " | ".join(cells_) + " |")
        out[os.path.basename(case)] = row
    print("\n".join(lines))
    with open(f"{args.outdir}/table.json", "w") as f:
        json.dump(out, f, indent=1)


def main():
    p = argparse.ArgumentParser()
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("cells")
    s.add_argument("n", type=int)
    s = sub.add_parser("prepare")
    s.add_argument("input")
    s.add_argument("output")
    s.add_argument("--alpha", type=float, required=True)
    s.add_argument("--beta", type=float, required=True)
    s.add_argument("--seed", type=int, required=True)
    s.add_argument("--temperature", type=float, default=1.0)
    s.add_argument("--rotational-temperature", type=float, default=0.0)
    s = sub.add_parser("analyse")
    s.add_argument("dir")
    s.add_argument("--segments", type=int, required=True)
    s = sub.add_parser("summary")
    s.add_argument("csv")
    s.add_argument("--first", type=float, default=20)
    s.add_argument("--last", type=float, default=40)
    s = sub.add_parser("theory")
    s.add_argument("--alpha", type=float, required=True)
    s.add_argument("--beta", type=float, required=True)
    s.add_argument("--inertia", type=float, default=Q_SOLID)
    s = sub.add_parser("table")
    s.add_argument("outdir")
    s.add_argument("--first", type=float, default=20)
    s.add_argument("--last", type=float, default=40)
    a = p.parse_args()
    if a.cmd == "cells":
        cells(a.n)
    elif a.cmd == "prepare":
        prepare(a)
    elif a.cmd == "analyse":
        analyse(a)
    elif a.cmd == "summary":
        print(json.dumps(summarise(a.csv, a.first, a.last)))
    elif a.cmd == "theory":
        print(json.dumps(theory(a.alpha, a.beta, a.inertia)))
    elif a.cmd == "table":
        table(a)


if __name__ == "__main__":
    main()
