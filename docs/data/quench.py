#!/usr/bin/env python3
"""The quench of docs/particles.md: a 2D gas that cooled freely into clusters
(quench-cool.toml) continued from its last state with white-noise driving
(quench-drive.toml, `initial = { run = "quench-cool" }`).

    haff run docs/data/quench-cool.toml --out quench-cool
    haff run docs/data/quench-drive.toml --out quench-drive
    python docs/data/quench.py quench-cool quench-drive docs/particles/quench.png

The figure: the structure factor at the smallest wave number of the box, S(k_min) (1 for
an ideal gas; (1 - phi)^3 / (1 + phi) ~ 0.34 for hard disks at phi = 0.25 without
clustering, Henderson's equation of state; far above 1 in clusters), and the temperature,
both against time over the two runs; and the density maps at the end of each run (the
fields' .vti files, read with meshio). Prints the numbers the docs quote.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402


def structure_at_smallest_k(run: Path) -> pd.DataFrame:
    s = pd.read_csv(run / "structure.csv")
    s = s[s.function == "S"]
    smallest = s.x.min()
    return s[s.x == smallest][["time", "collisions_per_particle", "value"]]


def last_density(run: Path) -> np.ndarray:
    last = sorted(run.glob("fields_*.vti"))[-1]
    mesh = meshio.read(last)
    data = mesh.point_data.get("density")
    if data is None:
        data = mesh.cell_data["density"][0]
    n = int(round(np.sqrt(data.size)))
    return np.asarray(data).reshape(n, n), last.name


def main(cool: Path, drive: Path, out: Path) -> None:
    sc, sd = structure_at_smallest_k(cool), structure_at_smallest_k(drive)
    tc, td = pd.read_csv(cool / "timeseries.csv"), pd.read_csv(drive / "timeseries.csv")
    t_end = tc.time.iloc[-1]
    fig = plt.figure(figsize=(10, 7.5), constrained_layout=True)
    grid = fig.add_gridspec(2, 2)
    ax = fig.add_subplot(grid[0, 0])
    ax.semilogy(sc.time, sc.value, "o-", label="cooling (quench-cool)")
    ax.semilogy(sd.time + t_end, sd.value, "s-", label="driven (quench-drive)")
    ax.axhline(0.75**3 / 1.25, color="grey", ls="--", label="hard disks, no clusters")
    ax.axvline(t_end, color="k", lw=0.8)
    ax.set_xlabel("time")
    ax.set_ylabel("S(k_min)")
    ax.legend(fontsize=8)
    ax = fig.add_subplot(grid[0, 1])
    ax.semilogy(tc.time, tc.temperature, label="cooling")
    ax.semilogy(td.time + t_end, td.temperature, label="driven")
    ax.axvline(t_end, color="k", lw=0.8)
    ax.set_xlabel("time")
    ax.set_ylabel("temperature")
    ax.legend(fontsize=8)
    maps = [(last_density(run), title)
            for run, title in [(cool, "end of cooling"), (drive, "end of driving")]]
    vmax = max(d.max() for (d, _), _ in maps)
    for k, ((density, name), title) in enumerate(maps):
        ax = fig.add_subplot(grid[1, k])
        image = ax.imshow(density.T, origin="lower", cmap="viridis", vmin=0, vmax=vmax)
        ax.set_title(f"{title}: number density ({name})", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        fig.colorbar(image, ax=ax, shrink=0.8)
        print(f"{title}: density field max {density.max():.3f}, "
              f"standard deviation {density.std():.3f}")
    fig.savefig(out, dpi=90)
    print(f"S(k_min): start {sc.value.iloc[0]:.3f}, end of cooling {sc.value.iloc[-1]:.2f}, "
          f"end of driving {sd.value.iloc[-1]:.3f} (mean of the last 5: "
          f"{sd.value.iloc[-5:].mean():.3f})")
    print(f"T: end of cooling {tc.temperature.iloc[-1]:.4g}, "
          f"end of driving {td.temperature.iloc[-1]:.4g}")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3]))
