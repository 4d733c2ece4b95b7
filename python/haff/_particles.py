"""Particle files: read a configuration another code (or haff) wrote, write one for
OVITO, LAMMPS, ASE or haff. Formats: ``csv`` (haff's columns), ``lammps-dump`` (a
``dump custom`` frame), ``xyz`` (extended XYZ with a ``Lattice``)."""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Sequence, Union

import numpy as np

from . import _haff
from ._haff import ConfigError

PathLike = Union[str, "os.PathLike[str]"]

#: The keys of a configuration dict besides ``box`` and ``positions``.
OPTIONAL = ("velocities", "diameters", "masses", "species", "spins", "time")


def read_configuration(path: PathLike, format: str, dimension: int = 3, frame: int = -1,
                       check: bool = True, box: Optional[Sequence[float]] = None
                       ) -> Dict[str, Any]:
    """Reads frame ``frame`` (0 the first, -1 the last) of a particle file.

    Returns a dict of numpy arrays: ``box`` (D sides; the box runs from the origin),
    ``positions`` (N, D), and what the file holds of ``velocities`` (N, D), ``diameters``
    (N,), ``masses`` (N,), ``species`` (N,) indices from 0, ``spins`` (N, 3), ``time``.
    With ``check`` (default) a configuration a run cannot start from — overlapping
    spheres, particles outside the box, non-finite values — raises ``haff.ConfigError``
    naming the file, the record and the field, as a bad line of the file does.
    ``format``: ``csv``, ``lammps-dump``, ``xyz`` or ``vtk`` (haff's snapshot ``.vtu``).
    ``box``: the sides of the box for a file that holds none (a ``.vtu`` not written by
    haff); a file's own box must agree with it.

    Example::

        c = haff.read_configuration("dump.lammpstrj", "lammps-dump")
        c["positions"].shape   # (N, 3)
    """
    sides = None if box is None else [float(x) for x in box]
    return _haff.read_configuration(os.fspath(path), str(format), int(dimension), int(frame),
                                    bool(check), sides)


def write_configuration(path: PathLike, format: str, configuration: Mapping[str, Any]) -> None:
    """Writes ``configuration`` (a dict as :func:`read_configuration` returns: ``box``,
    ``positions`` and any of ``velocities``, ``diameters``, ``masses``, ``species``,
    ``spins``, ``time``) in ``format``, after the checks of :func:`read_configuration`.
    Numbers are written in the shortest form that reads back to the same float64."""
    arrays = _arrays(configuration)
    time = configuration.get("time")
    _haff.write_configuration(os.fspath(path), str(format), *arrays,
                              None if time is None else float(time))


def _arrays(configuration: Mapping[str, Any], box_required: bool = True) -> tuple:
    """The arguments of the bindings for a configuration dict: box (empty if absent and
    not required), positions, velocities, diameters, masses, species, spins, as contiguous
    float64 arrays (species a list of ints)."""
    unknown = set(configuration) - {"box", "positions", *OPTIONAL}
    if unknown:
        raise ConfigError(f"configuration: unknown keys {sorted(unknown)}; allowed: box, "
                          f"positions, {', '.join(OPTIONAL)}")
    for key in ("box", "positions") if box_required else ("positions",):
        if key not in configuration:
            raise ConfigError(f"configuration: `{key}` is required")
    box = configuration.get("box")
    box = [] if box is None else [float(x) for x in np.atleast_1d(np.asarray(box, float))]
    positions = np.ascontiguousarray(configuration["positions"], dtype=float)
    if positions.ndim != 2:
        raise ConfigError(f"positions: an (N, D) array, not of shape {positions.shape}")
    d = len(box) or positions.shape[1]

    def matrix(key, width):
        value = configuration.get(key)
        if value is None:
            return None
        array = np.ascontiguousarray(value, dtype=float)
        if array.ndim == 1 and width == 1:
            array = array.reshape(-1, 1)
        return array

    def vector(key):
        value = configuration.get(key)
        return None if value is None else np.ascontiguousarray(value, dtype=float).ravel()

    species = configuration.get("species")
    if species is not None:
        species = [int(s) for s in np.asarray(species).ravel()]
        if any(s < 0 for s in species):
            raise ConfigError("species: indices from 0")
    return (box, matrix("positions", d), matrix("velocities", d), vector("diameters"),
            vector("masses"), species, matrix("spins", 3))
