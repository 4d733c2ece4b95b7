#!/usr/bin/env python3
"""Helpers of bench/peers/dynamo_shear.sh: DynamO's sheared granular gas set up and measured
the way `haff run` measures its `[shear]` runs (docs/peers-dynamo.md).

    dynamo_usf.py cells N                        -> "X Y Z": FCC unit cells with 4 X Y Z = N
    dynamo_usf.py prepare IN OUT --rate A --alpha E --temperature T --seed S
    dynamo_usf.py collisions OUTPUT.xml          -> the hard-sphere collisions of a dynarun
    dynamo_usf.py analyse DIR --rate A --first K --last M [--batches B] [--timeseries CSV]
    dynamo_usf.py table D1[,D2...] H1[,H2...]   -> a markdown table side by side (several
                                                  summaries: seeds, error from their scatter)

`prepare` rewrites a configuration of `dynamod -m 4` (monocomponent inelastic hard spheres
in Lees-Edwards boundaries, sigma = m = 1 in the file's units): the BC's shear rate
(`<BC Type="LE" Rate=...>`, dynamod writes 1), the hard-sphere interaction's Elasticity,
and the velocities: Maxwellian peculiar velocities at temperature T (total momentum zero,
rescaled to T exactly) plus the flow a y e_x, y measured from the box centre where DynamO
puts the zero of its flow (BCLeesEdwards::getStreamVelocity; positions in [-L/2, L/2)).

`analyse` reads the segments DIR/seg.K.config.xml (the configuration at the end of segment K)
and DIR/seg.K.output.xml (the Misc output of segment K). DynamO's Misc pressure tensor under
Lees-Edwards uses lab-frame velocities in its kinetic part (and averages it in time with
velocity jumps at the sliding faces not counted), so the kinetic part is recomputed here from
the peculiar velocities V = v - a y e_x of each segment's final configuration; the
collisional part is Misc's InteractionContribution, the time average over the segment.
Per segment: T = sum m V^2 / (3 N), P*_ab = (P^k_ab + P^c_ab) / (n T),
a* = a / nu0 with nu0 = n T / eta0, eta0 = 5 / (16 sigma^2) sqrt(m T / pi),
eta* = -P*_xy / a*. Means over segments K..M, errors from B batch means.
"""
import argparse
import json
import math
import random
import statistics
import sys
import xml.etree.ElementTree as ET


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


def particles(root):
    out = []
    for pt in root.iter("Pt"):
        p, v = pt.find("P"), pt.find("V")
        out.append(
            (
                [float(p.get(c)) for c in "xyz"],
                [float(v.get(c)) for c in "xyz"],
                pt,
            )
        )
    return out


def box(root):
    s = root.find("Simulation/SimulationSize")
    return [float(s.get(c)) for c in "xyz"]


def prepare(args):
    tree = ET.parse(args.input)
    root = tree.getroot()
    bc = root.find("Simulation/BC")
    if bc.get("Type") != "LE":
        sys.exit("not a Lees-Edwards configuration (dynamod -m 4)")
    bc.set("Rate", repr(args.rate))
    bc.set("DXD", "0")
    for inter in root.iter("Interaction"):
        if inter.get("Type") == "HardSphere":
            inter.set("Elasticity", repr(args.alpha))
            if float(inter.get("Diameter")) != 1.0:
                sys.exit("expected Diameter 1 (dynamod's unit of length)")
    for sp in root.iter("Species"):
        if float(sp.get("Mass")) != 1.0:
            sys.exit("expected Mass 1")
    rng = random.Random(args.seed)
    parts = particles(root)
    n = len(parts)
    vel = [[rng.gauss(0.0, 1.0) for _ in range(3)] for _ in range(n)]
    mean = [sum(v[c] for v in vel) / n for c in range(3)]
    vel = [[v[c] - mean[c] for c in range(3)] for v in vel]
    t = sum(v[c] ** 2 for v in vel for c in range(3)) / (3 * n)
    scale = math.sqrt(args.temperature / t)
    for (pos, _, pt), v in zip(parts, vel):
        v = [c * scale for c in v]
        v[0] += args.rate * pos[1]
        node = pt.find("V")
        for c, x in zip("xyz", v):
            node.set(c, repr(x))
    tree.write(args.output, xml_declaration=True, encoding="utf-8")


def collisions(path):
    root = ET.parse(path).getroot()
    total = 0
    for e in root.iter("Entry"):
        if e.get("Type") == "Interaction" and e.get("Event") == "CORE":
            total += int(e.get("Count"))
    return total


def matrix(text):
    vals = [float(x) for x in text.split()]
    return [vals[0:3], vals[3:6], vals[6:9]]


def segment(directory, k, rate):
    conf = ET.parse(f"{directory}/seg.{k}.config.xml").getroot()
    out = ET.parse(f"{directory}/seg.{k}.output.xml").getroot()
    sides = box(conf)
    vol = sides[0] * sides[1] * sides[2]
    parts = particles(conf)
    n = len(parts)
    dens = n / vol
    pk = [[0.0] * 3 for _ in range(3)]
    lab = [[0.0] * 3 for _ in range(3)]
    for pos, v, _ in parts:
        u = list(v)
        u[0] -= rate * pos[1]
        for a in range(3):
            for b in range(3):
                pk[a][b] += u[a] * u[b] / vol
                lab[a][b] += v[a] * v[b] / vol
    temp = (pk[0][0] + pk[1][1] + pk[2][2]) / (3 * dens)
    pressure = out.find("Misc/Pressure")
    pc = matrix(pressure.find("InteractionContribution").text)
    ptot_misc = matrix(pressure.find("Tensor").text)
    nt = dens * temp
    nu0 = 16.0 / 5.0 * dens * math.sqrt(math.pi * temp)
    astar = rate / nu0
    pstar = {
        "pxx": (pk[0][0] + pc[0][0]) / nt,
        "pyy": (pk[1][1] + pc[1][1]) / nt,
        "pzz": (pk[2][2] + pc[2][2]) / nt,
        "pxy": (pk[0][1] + pc[0][1]) / nt,
    }
    dur = out.find("Misc/Duration")
    timing = out.find("Misc/Timing")
    return {
        "temperature": temp,
        "reduced_shear_rate": astar,
        **pstar,
        "reduced_viscosity": -pstar["pxy"] / astar,
        "viscosity": -(pk[0][1] + pc[0][1]) / rate,
        "collisional_pxx": pc[0][0] / nt,
        "collisional_pxy": pc[0][1] / nt,
        "misc_lab_pxx": ptot_misc[0][0] / nt,
        "misc_lab_pxy": ptot_misc[0][1] / nt,
        "snapshot_lab_pxx": (lab[0][0] + pc[0][0]) / nt,
        "_time": float(dur.get("Time")),
        "_collisions": collisions(f"{directory}/seg.{k}.output.xml"),
        "_runtime": float(timing.get("RuntimeSeconds")),
        "_n": n,
        "_density": dens,
    }


def analyse(args):
    segs = [segment(args.dir, k, args.rate) for k in range(args.first, args.last + 1)]
    if args.timeseries:
        rows = [segment(args.dir, k, args.rate) for k in range(1, args.first)] + segs
        with open(args.timeseries, "w") as f:
            f.write("segment,time,collisions_per_particle,temperature,reduced_shear_rate,pxx,pyy,pzz,pxy\n")
            t = c = 0.0
            for k, s in enumerate(rows, 1):
                t += s["_time"]
                c += 2.0 * s["_collisions"] / s["_n"]
                f.write(f"{k},{t},{c},{s['temperature']},{s['reduced_shear_rate']},"
                        f"{s['pxx']},{s['pyy']},{s['pzz']},{s['pxy']}\n")
    keys = [k for k in segs[0] if not k.startswith("_")]
    nb = min(args.batches, len(segs))
    size = len(segs) // nb
    result = {}
    for key in keys:
        values = [s[key] for s in segs]
        batches = [
            statistics.fmean(values[i * size:(i + 1) * size]) for i in range(nb)
        ]
        err = statistics.stdev(batches) / math.sqrt(nb) if nb > 1 else float("nan")
        result[key] = {"mean": statistics.fmean(values), "error": err}
    print(
        json.dumps(
            {
                "peer": "DynamO",
                "particles": segs[0]["_n"],
                "density": segs[0]["_density"],
                "shear_rate": args.rate,
                "segments": len(segs),
                "batches": nb,
                "collisions": sum(s["_collisions"] for s in segs),
                "time": sum(s["_time"] for s in segs),
                "rheology": result,
            },
            indent=1,
        )
    )


def combine(paths, rheology):
    """Means of one run (its batch errors) or of several seeds (error: their scatter)."""
    runs = [rheology(json.load(open(p))) for p in paths]
    if len(runs) == 1:
        return runs[0]
    out = {}
    for key in runs[0]:
        if not isinstance(runs[0][key], dict) or "mean" not in runs[0][key]:
            continue
        vals = [r[key]["mean"] for r in runs]
        out[key] = {
            "mean": statistics.fmean(vals),
            "error": statistics.stdev(vals) / math.sqrt(len(vals)),
        }
    return out


def table(args):
    dr = combine(args.dynamo.split(","), lambda j: j["rheology"])
    hr = combine(args.haff.split(","), lambda j: j["rheology"])
    rows = [
        ("T (steady)", "temperature"),
        ("a*", "reduced_shear_rate"),
        ("P*_xx", "pxx"),
        ("P*_yy", "pyy"),
        ("P*_zz", "pzz"),
        ("P*_xy", "pxy"),
        ("eta*", "reduced_viscosity"),
    ]
    print("| quantity | DynamO | haff | difference / combined error |")
    print("|---|---|---|---|")
    for label, key in rows:
        dv, de = dr[key]["mean"], dr[key]["error"]
        hv, he = hr[key]["mean"], hr[key]["error"]
        z = (dv - hv) / math.hypot(de, he)
        print(f"| {label} | {dv:.4f} ± {de:.4f} | {hv:.4f} ± {he:.4f} | {z:+.1f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("cells")
    c.add_argument("n", type=int)
    p = sub.add_parser("prepare")
    p.add_argument("input")
    p.add_argument("output")
    p.add_argument("--rate", type=float, required=True)
    p.add_argument("--alpha", type=float, required=True)
    p.add_argument("--temperature", type=float, default=1.0)
    p.add_argument("--seed", type=int, default=1)
    k = sub.add_parser("collisions")
    k.add_argument("output")
    a = sub.add_parser("analyse")
    a.add_argument("dir")
    a.add_argument("--rate", type=float, required=True)
    a.add_argument("--first", type=int, required=True)
    a.add_argument("--last", type=int, required=True)
    a.add_argument("--batches", type=int, default=10)
    a.add_argument("--timeseries", help="also write every segment 1..last to this CSV")
    t = sub.add_parser("table")
    t.add_argument("dynamo", help="DynamO summary.json, or several joined by commas (seeds)")
    t.add_argument("haff", help="haff summary.json, or several joined by commas (seeds)")
    args = ap.parse_args()
    if args.cmd == "cells":
        cells(args.n)
    elif args.cmd == "prepare":
        prepare(args)
    elif args.cmd == "collisions":
        print(collisions(args.output))
    elif args.cmd == "analyse":
        analyse(args)
    else:
        table(args)


if __name__ == "__main__":
    main()
