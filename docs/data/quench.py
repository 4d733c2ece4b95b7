#!/usr/bin/env python3
"""The quench of docs/particles.md: a 2D gas that cooled freely into clusters
(quench-cool.toml) continued from its last state with white-noise driving
(quench-drive.toml, `initial = { run = "quench-cool" }`).

    haff run docs/data/quench-cool.toml --out quench-cool
    haff run docs/data/quench-drive.toml --out quench-drive
    haff run docs/data/quench-reference.toml --out quench-reference
    python docs/data/quench.py quench-cool quench-drive quench-reference docs/particles/quench.png

The figure: the structure factor at the smallest wave number of the box, S(k_min) (far
above 1 in clusters), against collisions per particle over the two runs, with the band of
the driven state reached from a homogeneous start (quench-reference.toml, samples from 100
collisions per particle on); the temperature; and the density maps at the end of each run
(the fields' .vti files). Prints the numbers the docs quote.
"""

import base64
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402


def structure_at_smallest_k(run: Path) -> pd.DataFrame:
    s = pd.read_csv(run / "structure.csv")
    s = s[s.function == "S"]
    smallest = s.x.min()
    return s[s.x == smallest][["time", "collisions_per_particle", "value"]]


def last_density(run: Path) -> np.ndarray:
    """The density cells of the run's last fields file: haff's .vti holds them as a binary
    DataArray (base64 of a UInt64 byte count, then little-endian float64s), x fastest."""
    last = sorted(run.glob("fields_*.vti"))[-1]
    array = next(a for a in ET.parse(last).iter("DataArray") if a.get("Name") == "density")
    raw = base64.b64decode(array.text.strip())
    count = int(np.frombuffer(raw[:8], "<u8")[0])
    data = np.frombuffer(raw[8:8 + count], "<f8")
    n = int(round(np.sqrt(data.size)))
    return data.reshape(n, n).T, last.name


def main(cool: Path, drive: Path, reference: Path, out: Path) -> None:
    sc, sd = structure_at_smallest_k(cool), structure_at_smallest_k(drive)
    sr = structure_at_smallest_k(reference)
    steady = sr[sr.collisions_per_particle >= 100].value
    tc, td = pd.read_csv(cool / "timeseries.csv"), pd.read_csv(drive / "timeseries.csv")
    c_end = tc.collisions_per_particle.iloc[-1]
    fig = plt.figure(figsize=(10, 7.5), constrained_layout=True)
    grid = fig.add_gridspec(2, 2)
    ax = fig.add_subplot(grid[0, 0])
    ax.semilogy(sc.collisions_per_particle, sc.value, "o-", label="cooling (quench-cool)")
    ax.semilogy(sd.collisions_per_particle + c_end, sd.value, "s-",
                label="driven from the clusters (quench-drive)")
    ax.axhspan(steady.min(), steady.max(), color="grey", alpha=0.3,
               label="driven from a homogeneous start (quench-reference)")
    ax.axvline(c_end, color="k", lw=0.8)
    ax.set_xlabel("collisions per particle")
    ax.set_ylabel("S(k_min)")
    ax.legend(fontsize=8)
    ax = fig.add_subplot(grid[0, 1])
    ax.semilogy(tc.collisions_per_particle, tc.temperature, label="cooling")
    ax.semilogy(td.collisions_per_particle + c_end, td.temperature, label="driven")
    ax.axvline(c_end, color="k", lw=0.8)
    ax.set_xlabel("collisions per particle")
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
          f"driven: {', '.join(f'{v:.3g}' for v in sd.value)}; reference (c >= 100): "
          f"{steady.min():.3g} .. {steady.max():.3g}, mean {steady.mean():.3g}")
    print(f"T: end of cooling {tc.temperature.iloc[-1]:.4g}, "
          f"end of driving {td.temperature.iloc[-1]:.4g}")


if __name__ == "__main__":
    main(*(Path(a) for a in sys.argv[1:5]))
