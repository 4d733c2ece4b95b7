"""The worked study of docs/studies.md: a2 and the cooling rate per collision of the
homogeneous cooling state against restitution, by DSMC, 8 seeds per point, against van
Noije & Ernst and the Sonine hierarchy.

    python hcs.py threads OUT     # haff.study on threads of this process (jobs=2)
    python hcs.py processes OUT   # a concurrent.futures.ProcessPoolExecutor
    python hcs.py dask OUT        # a dask.distributed LocalCluster
    python hcs.py table OUT [PNG] # the table from OUT (any of the three, or `haff study`),
                                  # and its figure

The run file and the study are gas.toml and study.toml beside this script (the same study
as `haff study study.toml --out OUT --jobs 2`).
"""

import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

import haff

HERE = Path(__file__).resolve().parent
VARY = {"collision.restitution": [0.3, 0.5, 0.7, 0.8, 0.9]}
SEEDS = 8
#: The samples averaged: from 10 collisions per particle on (the HCS reached; a2 relaxes
#: within a few collisions per particle).
FROM = 10.0


def run(how: str, out: Path):
    clock = time.perf_counter()
    base = HERE / "gas.toml"
    if how == "threads":
        result = haff.study(base, VARY, seeds=SEEDS, output_dir=out, jobs=2)
    elif how == "processes":
        from concurrent.futures import ProcessPoolExecutor
        with ProcessPoolExecutor(2) as pool:
            result = haff.study(base, VARY, seeds=SEEDS, output_dir=out, executor=pool)
    elif how == "dask":
        from distributed import Client, LocalCluster
        with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
            result = haff.study(base, VARY, seeds=SEEDS, output_dir=out, executor=client)
    else:
        raise SystemExit(__doc__)
    print(f"{how}: {len(result.runs)} runs in {time.perf_counter() - clock:.1f} s")
    return result


def table(out: Path) -> pd.DataFrame:
    """Per point: a2 and -d ln T / d(collisions per particle) of each run over the samples
    from FROM on (a2 averaged, the slope by least squares), then mean and standard error
    over the seeds; the theories beside them."""
    runs = pd.read_json(out / "study.json", typ="series")["runs"]
    rows = []
    for eps in VARY["collision.restitution"]:
        point = VARY["collision.restitution"].index(eps)
        a2s, rates = [], []
        for run in (r for r in runs if r["point"] == point and r["state"] == "complete"):
            series = pd.read_csv(out / run["dir"] / "timeseries.csv")
            late = series[series["collisions_per_particle"] >= FROM]
            a2s.append(late["a2"].mean())
            slope = np.polyfit(late["collisions_per_particle"], np.log(late["temperature"]), 1)[0]
            rates.append(-slope)
        n = len(a2s)
        a2, a2_error = np.mean(a2s), np.std(a2s, ddof=1) / np.sqrt(n)
        rate, rate_error = np.mean(rates), np.std(rates, ddof=1) / np.sqrt(n)
        full = haff.theory.sonine(3, eps, order=6, linear=False)
        rows.append({
            "eps": eps, "seeds": n,
            "a2": a2, "a2_se": a2_error,
            "a2_vNE": haff.theory.a2(3, eps),
            "a2_second_sonine": haff.theory.sonine(3, eps, order=3)[0],
            "a2_hierarchy_K6": np.nan if full is None else full[0],
            "cooling": rate, "cooling_se": rate_error,
            "cooling_maxwell": haff.theory.cooling_per_collision(eps),
            "cooling_sonine_measured_a2": haff.theory.cooling_per_collision(eps, a2),
        })
    return pd.DataFrame(rows)


def figure(rows: pd.DataFrame, png: Path) -> None:
    """a2 against eps with the theories; the cooling rate relative to the Maxwellian one."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    eps = np.linspace(0.25, 1.0, 76)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.errorbar(rows["eps"], rows["a2"], rows["a2_se"], fmt="o", color="k",
                  label="DSMC, 8 seeds (haff study)")
    left.plot(eps, [haff.theory.a2(3, e) for e in eps], "--", label="van Noije & Ernst")
    left.plot(eps, [haff.theory.sonine(3, e, order=3)[0] for e in eps], ":",
              label="second Sonine (linear)")
    full = [haff.theory.sonine(3, e, order=6, linear=False) for e in eps]
    left.plot(eps, [np.nan if f is None else f[0] for f in full], "-", lw=1,
              label="Sonine hierarchy K = 6 (all terms)")
    left.set(xlabel="restitution eps", ylabel="a2 of the HCS")
    left.legend(fontsize=8)
    maxwell = rows["cooling_maxwell"]
    right.errorbar(rows["eps"], rows["cooling"] / maxwell, rows["cooling_se"] / maxwell,
                   fmt="o", color="k", label="DSMC: -d ln T / d(collisions per particle)")
    right.plot(rows["eps"], rows["cooling_sonine_measured_a2"] / maxwell, "x",
               label="(1 + 3 a2/16)/(1 - a2/16), a2 measured")
    right.plot(eps, [(1 + 3 * a / 16) / (1 - a / 16)
                     for a in (haff.theory.a2(3, e) for e in eps)], "--",
               label="the same, a2 of van Noije & Ernst")
    right.set(xlabel="restitution eps", ylabel="cooling per collision / (1 - eps^2)/3")
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    how, out = sys.argv[1], Path(sys.argv[2])
    if how != "table":
        run(how, out)
    rows = table(out)
    with pd.option_context("display.width", 200, "display.precision", 5):
        print(rows.to_string(index=False))
    if len(sys.argv) == 4:
        figure(rows, Path(sys.argv[3]))
