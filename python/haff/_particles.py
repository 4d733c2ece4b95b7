"""Particle files: read a configuration another code (or haff) wrote, write one for
OVITO, LAMMPS, ASE or haff. Formats: ``csv`` (haff's columns), ``lammps-dump`` (a
``dump custom`` frame), ``lammps-data`` (``atom_style sphere``), ``xyz`` (extended XYZ with
a ``Lattice``), ``vtk`` (haff's ``.vtu`` snapshots), ``h5md`` (HDF5; a package built with
the feature ``h5md``)."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _haff
from ._haff import ConfigError

PathLike = Union[str, "os.PathLike[str]"]
Floats = npt.NDArray[np.float64]

#: The keys of a configuration dict besides ``box`` and ``positions``.
OPTIONAL = ("velocities", "diameters", "masses", "species", "spins", "time")


def read_configuration(path: PathLike, format: str, dimension: int = 3, frame: int = -1,
                       check: bool = True, box: Optional[Sequence[float]] = None
                       ) -> Dict[str, Any]:
    """Reads one frame of a particle file as numpy arrays.

    The reader of ``[system] initial = { file = ... }``: the same parsing and checks as a
    run starting from the file (docs/particles.md).

    Parameters
    ----------
    path : str or path
        The particle file.
    format : str
        ``csv``, ``lammps-dump``, ``lammps-data``, ``xyz``, ``vtk`` (haff's snapshot
        ``.vtu``) or ``h5md`` (with the feature ``h5md``).
    dimension : {1, 2, 3}, default 3
        The dimension of the configuration (a 2D gas in an XYZ file has z = 0).
    frame : int, default -1
        The frame of a trajectory: 0 the first, -1 the last.
    check : bool, default True
        Refuse a configuration a run cannot start from: overlapping spheres, particles
        outside the box, non-finite values.
    box : sequence of float, optional
        The sides of the box (in the file's length unit) for a file that holds none (a
        ``.vtu`` not written by haff); a file's own box must agree with it.

    Returns
    -------
    dict
        ``box`` (D sides; the box runs from the origin), ``positions`` (N, D), and what
        the file holds of ``velocities`` (N, D), ``diameters`` (N,), ``masses`` (N,),
        ``species`` (N,) indices from 0, ``spins`` (N, 3) and ``time`` (a float), in the
        file's units (haff's reduced units for files haff wrote).

    Raises
    ------
    ConfigError
        A bad line or field of the file, or (with `check`) a configuration a run cannot
        start from: the message names the file, the record and the field.

    See Also
    --------
    write_configuration, Simulation : ``Simulation(config, initial=c)`` starts from it.

    Examples
    --------
    >>> import haff
    >>> haff.write_configuration("two.xyz", "xyz", {
    ...     "box": [4.0, 4.0, 4.0], "positions": [[1.0, 1.0, 1.0], [2.5, 1.0, 1.0]],
    ...     "velocities": [[0.5, 0.0, 0.0], [-0.5, 0.0, 0.0]]})
    >>> c = haff.read_configuration("two.xyz", "xyz")
    >>> sorted(c)
    ['box', 'diameters', 'positions', 'species', 'velocities']
    >>> c["positions"]
    array([[1. , 1. , 1. ],
           [2.5, 1. , 1. ]])
    """
    sides = None if box is None else [float(x) for x in box]
    return _haff.read_configuration(os.fspath(path), str(format), int(dimension), int(frame),
                                    bool(check), sides)


def write_configuration(path: PathLike, format: str, configuration: Mapping[str, Any]) -> None:
    """Writes a configuration as a particle file, after the checks of a run's start.

    Numbers are written in the shortest form that reads back to the same float64, so
    that :func:`read_configuration` gives the arrays back bit for bit.

    Parameters
    ----------
    path : str or path
        The file to write (replaced if it exists).
    format : str
        As for :func:`read_configuration`.
    configuration : dict of array_like
        As :func:`read_configuration` returns it: ``box`` (D sides), ``positions``
        (N, D) and any of ``velocities`` (N, D), ``diameters`` (N,), ``masses`` (N,),
        ``species`` (N,) indices from 0, ``spins`` (N, 3), ``time``.

    Returns
    -------
    None

    Raises
    ------
    ConfigError
        An unknown key, a missing ``box`` or ``positions``, arrays of the wrong shape, or
        a configuration a run cannot start from (overlaps, particles outside the box,
        non-finite values), naming the record.
    OSError
        The file cannot be written.

    Examples
    --------
    >>> import haff
    >>> haff.write_configuration("two.csv", "csv", {
    ...     "box": [4.0, 4.0, 4.0], "positions": [[1.0, 1.0, 1.0], [2.5, 1.0, 1.0]]})
    >>> print(open("two.csv").read())
    # box = 4 4 4
    x,y,z
    1,1,1
    2.5,1,1
    <BLANKLINE>
    >>> haff.write_configuration("overlap.csv", "csv", {
    ...     "box": [4.0, 4.0, 4.0], "positions": [[1.0, 1.0, 1.0], [1.5, 1.0, 1.0]]})
    Traceback (most recent call last):
    ...
    haff.ConfigError: overlap.csv: records 0 and 1: the spheres overlap by 5e-1 (of the sum of their radii 1): allowed: no overlap
    """
    arrays = _arrays(configuration)
    time = configuration.get("time")
    _haff.write_configuration(os.fspath(path), str(format), *arrays,
                              None if time is None else float(time))


Arrays = Tuple[List[float], Floats, Optional[Floats], Optional[Floats], Optional[Floats],
               Optional[List[int]], Optional[Floats]]


def _arrays(configuration: Mapping[str, Any], box_required: bool = True) -> Arrays:
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
    given = configuration.get("box")
    box = [] if given is None else [float(x) for x in np.atleast_1d(np.asarray(given, float))]
    positions = np.ascontiguousarray(configuration["positions"], dtype=float)
    if positions.ndim != 2:
        raise ConfigError(f"positions: an (N, D) array, not of shape {positions.shape}")
    d = len(box) or positions.shape[1]

    def matrix(key: str, width: int) -> Optional[Floats]:
        value = configuration.get(key)
        if value is None:
            return None
        array = np.ascontiguousarray(value, dtype=float)
        if array.ndim == 1 and width == 1:
            array = array.reshape(-1, 1)
        return array

    def vector(key: str) -> Optional[Floats]:
        value = configuration.get(key)
        return None if value is None else np.ascontiguousarray(value, dtype=float).ravel()

    species: Optional[List[int]] = None
    if configuration.get("species") is not None:
        species = [int(s) for s in np.asarray(configuration["species"]).ravel()]
        if any(s < 0 for s in species):
            raise ConfigError("species: indices from 0")
    return (box, positions, matrix("velocities", d), vector("diameters"), vector("masses"),
            species, matrix("spins", 3))
