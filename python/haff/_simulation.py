"""Granular-gas runs from Python, on the library run driver that ``haff run`` drives."""

from __future__ import annotations

import json
import math
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _haff
from ._haff import ConfigError
from ._progress import progress_callback

if TYPE_CHECKING:  # the DataFrame methods import pandas when called
    import pandas

Config = Union[Mapping[str, Any], str, "os.PathLike[str]"]
PathLike = Union[str, "os.PathLike[str]"]
Floats = npt.NDArray[np.float64]

#: The observers of ``[output]`` that write files during the run, and what they write.
_FILE_OUTPUTS = (("fields", "fields_NNNNNN.vti"),
                 ("snapshots", "snapshot_NNNNNN.vtu or trajectory"))


def _toml_value(value: Any, key: str) -> str:
    """One TOML value (inline tables and arrays nested)."""
    if isinstance(value, bool) or isinstance(value, np.bool_):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, Mapping):
        items = ", ".join(f"{_toml_key(k)} = {_toml_value(v, f'{key}.{k}')}"
                          for k, v in value.items())
        return "{ " + items + " }" if items else "{}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v, key) for v in list(value)) + "]"
    if value is None:
        raise ConfigError(f"{key}: None is not a value; leave the key out for its default")
    raise ConfigError(f"{key}: a value of type {type(value).__name__} is not allowed")


def _toml_key(key: Any) -> str:
    if not isinstance(key, str):
        raise ConfigError(f"{key!r}: keys are strings")
    return key if key and all(c.isalnum() or c in "_-" for c in key) else json.dumps(key)


def config_to_toml(config: Mapping[str, Any]) -> str:
    """A dict with the run file's structure as TOML text (sections as tables).

    Parameters
    ----------
    config : dict
        Section name -> dict of keys (a list of dicts: an array of inline tables); a
        value that is not a dict is a top-level key.

    Returns
    -------
    str
        The run file's text, which :class:`Simulation` parses as ``haff run`` would.

    Examples
    --------
    >>> print(config_to_toml({"collision": {"law": "constant", "restitution": 0.9}}))
    [collision]
    law = "constant"
    restitution = 0.9
    <BLANKLINE>
    """
    lines: List[str] = []
    for section, body in config.items():
        if not isinstance(body, Mapping):
            lines.insert(0, f"{_toml_key(section)} = {_toml_value(body, str(section))}")
            continue
        lines.append(f"[{_toml_key(section)}]")
        for key, value in body.items():
            lines.append(f"{_toml_key(key)} = {_toml_value(value, f'{section}.{key}')}")
    return "\n".join(lines) + "\n"


def _json(text: str) -> Dict[str, Any]:
    """A JSON object the bindings wrote (summary.json's parts, the description)."""
    value: Dict[str, Any] = json.loads(text)
    return value


def _build(config: Config, initial: Optional[Mapping[str, Any]] = None) -> _haff._Simulation:
    if initial is not None:
        return _build_with_initial(config, initial)
    if isinstance(config, Mapping):
        return _haff._Simulation.from_toml(config_to_toml(config), "<dict>")
    if isinstance(config, os.PathLike):
        return _haff._Simulation.from_path(os.fspath(config))
    if isinstance(config, str):
        if os.path.isfile(config):
            return _haff._Simulation.from_path(config)
        if "=" in config or "[" in config or "\n" in config:
            return _haff._Simulation.from_toml(config, "<toml text>")
        raise ConfigError(f"{config}: no such run file (or give TOML text or a dict)")
    raise ConfigError(
        f"config: a dict, a path to a TOML file or TOML text, not {type(config).__name__}")


def _build_with_initial(config: Config, initial: Mapping[str, Any]) -> _haff._Simulation:
    """A run whose particles are the arrays of `initial` (see :class:`Simulation`)."""
    from ._particles import _arrays
    if not isinstance(initial, Mapping):
        raise ConfigError(
            f"initial: a dict of arrays (positions, ...), not {type(initial).__name__}")
    if isinstance(config, Mapping):
        text, origin = config_to_toml(config), "<dict>"
    elif isinstance(config, os.PathLike) or (isinstance(config, str) and os.path.isfile(config)):
        with open(config, encoding="utf-8") as f:
            text, origin = f.read(), os.fspath(config)
    elif isinstance(config, str):
        text, origin = config, "<toml text>"
    else:
        raise ConfigError(
            f"config: a dict, a path to a TOML file or TOML text, not {type(config).__name__}")
    return _haff._Simulation.with_initial(text, origin, *_arrays(initial, box_required=False))


class Simulation:
    """A granular-gas run: the run of ``haff run``, from Python.

    A Simulation is one run of a run file — event-driven MD, DSMC or soft-sphere MD of a
    gas in the periodic box or in a container, cooling, driven or sheared, one species or
    a mixture — built from the same description, checked by the same validation and
    advanced by the same run driver (the Rust crate ``haff-sim``) as the ``haff``
    command: the same description and seed give the same numbers as ``haff run``, bit
    for bit. It is made ready to run (particles placed, velocities drawn) and runs when
    :meth:`run` or :meth:`advance` is called; its samples are then the columns of the
    command's files as numpy arrays or pandas DataFrames, and :meth:`write` writes the
    files themselves.

    Parameters
    ----------
    config : dict, str or path
        The run description. A dict with the structure of the TOML run file, section
        name -> dict of keys (``{"system": {...}, "collision": {...}, "run": {...}}``,
        plus ``"output"``, ``"shear"``, ``"field"``, ``"wall": [{...}, ...]`` and the
        other tables and arrays of tables of the run file), with the same keys, values
        and defaults; the keys are listed in docs/guide/reference.md (``haff schema``
        prints them as a JSON Schema). Or a path to a TOML run file, or TOML text.
        Quantities are in the run's units: the particle diameter, mass and initial
        temperature are 1 unless given, so that lengths are in diameters sigma and
        times in sigma sqrt(m / T0) (haff's reduced units).
    output_dir : str or path, optional
        The output directory, as ``haff run --out DIR``: the field and snapshot files of
        ``[output]`` are written there during the run (see :attr:`output_dir`), and
        :meth:`write` writes there by default.
    force : bool, default False
        Replace another run's outputs in `output_dir` (``haff run --force``).
    initial : dict of array_like, optional
        The particles to start from instead of a placement, as
        :func:`haff.read_configuration` returns them: ``positions`` (N, D) and any of
        ``box`` (D sides; else ``system.box``), ``velocities`` (N, D; else drawn at
        ``system.temperature``), ``diameters`` (N,), ``masses`` (N,), ``species`` (N,),
        ``spins`` (N, 3); a ``time`` is ignored (the run starts at 0). Checked as a
        particle file (``system.initial``): overlapping spheres, particles outside the
        box and non-finite values raise :class:`haff.ConfigError` naming the record;
        ``system.particles``, ``packing_fraction`` and ``species`` are refused (the
        arrays make them).

    Attributes
    ----------
    timeseries : dict of numpy.ndarray
        The samples so far, the columns of ``timeseries.csv``.
    species_timeseries : dict of numpy.ndarray or None
        A mixture's per-species samples, the columns of ``species.csv``.
    velocity_histograms : list of dict
        The histograms taken at ``run.histogram_at``.
    time, temperature, collisions, events, collisions_per_particle, energy_lost : number
        Where the run stands now.
    positions, velocities, radii, masses : numpy.ndarray
        The particles now (copies).
    complete : bool
        Whether every sample has been taken.
    config : dict
        The description with every default filled in.
    output_dir : pathlib.Path or None
        Where field and snapshot files are written.
    initial_state : dict or None
        How a dense start was made.
    wall_seconds : float
        Wall-clock seconds spent building and running.

    Methods
    -------
    run, advance
        Run to the end, or to a time or a number of collisions per particle.
    timeseries_frame, walls, pressure, profiles
        Results as pandas DataFrames (the columns of the command's CSV files).
    modes, structure, rheology, green_kubo, contact_statistics
        Results of observers and engines, as ``modes.csv``, ``structure.csv`` and
        ``summary.json`` have them.
    field_files, snapshot_files
        The files written during the run.
    save, load, write, set_output_dir
        Check-points (``haff run --resume``) and the files of ``haff run --out DIR``.

    Raises
    ------
    ConfigError
        A bad description, before anything runs: the message names the key and what is
        allowed, e.g. ``system.packing_fraction: 2 is out of range; allowed: ...``, and
        a misspelt key or value gets the closest allowed name.

    See Also
    --------
    study : many runs over parameters and seeds, with error bars.

    Notes
    -----
    Runs go on with the GIL released, in pieces of about 0.1 s; between pieces the
    progress callback is called and signals are looked at, so that Ctrl-C raises
    ``KeyboardInterrupt`` and leaves the run where it stopped, ready to go on (``run()``
    again finishes it as an uninterrupted run would).

    Examples
    --------
    >>> import haff
    >>> sim = haff.Simulation({
    ...     "system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
    ...     "collision": {"law": "constant", "restitution": 0.9},
    ...     "run": {"collisions_per_particle": 10, "samples": 6}})
    >>> sim
    <haff.Simulation 3D N=500 engine=event-driven t=0 samples=0 complete=False>
    >>> sim.run(progress=False)
    <haff.Simulation 3D N=500 engine=event-driven t=6.73116 samples=6 complete=True>
    >>> sim.timeseries["temperature"].round(4)
    array([1.    , 0.9991, 0.9958, 0.9818, 0.8899, 0.5328])

    TOML text (or a file's path) gives the same run:

    >>> text = '''
    ... [system]
    ... particles = 500
    ... packing_fraction = 0.1
    ... seed = 1
    ... [collision]
    ... law = "constant"
    ... restitution = 0.9
    ... [run]
    ... collisions_per_particle = 10
    ... samples = 6
    ... '''
    >>> same = haff.Simulation(text).run(progress=False)
    >>> bool((same.timeseries["temperature"] == sim.timeseries["temperature"]).all())
    True
    """

    def __init__(self, config: Config, output_dir: Optional[PathLike] = None,
                 force: bool = False, initial: Optional[Mapping[str, Any]] = None):
        self._sim = _build(config, initial)
        if output_dir is not None:
            self.set_output_dir(output_dir, force=force)

    @classmethod
    def load(cls, path: PathLike, output_dir: Optional[PathLike] = None,
             force: bool = False) -> Simulation:
        """The run saved by :meth:`save`, ready to go on bit for bit.

        Checked as ``haff run --resume`` checks a check-point (its integrity and its
        description). The output directory is not part of a check-point: give
        `output_dir` again for a run that writes fields or snapshots (a ``haff run``
        directory may be its own).

        Parameters
        ----------
        path : str or path
            A check-point file, or a directory holding ``checkpoint.bin`` (such as a
            ``haff run --checkpoint-every K`` output directory).
        output_dir : str or path, optional
            As for :class:`Simulation`.
        force : bool, default False
            As for :class:`Simulation`.

        Returns
        -------
        Simulation
            The run where it was saved.

        Raises
        ------
        ConfigError
            A missing, damaged or foreign file.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas)
        >>> sim.advance(collisions_per_particle=5.0)
        True
        >>> sim.save("half.bin")
        >>> again = haff.Simulation.load("half.bin")
        >>> again.collisions_per_particle, again.complete
        (5.0, False)
        >>> a = sim.run(progress=False).timeseries["temperature"]
        >>> b = again.run(progress=False).timeseries["temperature"]
        >>> bool((a == b).all())
        True
        """
        self = cls.__new__(cls)
        self._sim = _haff._Simulation.load(os.fspath(path))
        if output_dir is not None:
            self.set_output_dir(output_dir, force=force)
        return self

    @property
    def output_dir(self) -> Optional[Path]:
        """The output directory, or None until one is set.

        The field files (``fields_NNNNNN.vti``) and snapshots (``snapshot_NNNNNN.vtu``)
        of ``[output]`` are written there during the run, NNNNNN the sample number. A run
        asking for them without one raises :class:`haff.ConfigError` naming
        ``output.fields`` or ``output.snapshots`` before it starts. Setting it
        (``sim.output_dir = DIR``) claims the directory as ``haff run --out`` does
        (:meth:`set_output_dir`).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas)
        >>> print(sim.output_dir)
        None
        >>> sim.output_dir = "cooling"
        >>> sim.output_dir
        PosixPath('cooling')
        """
        path = self._sim.output_dir
        return None if path is None else Path(path)

    @output_dir.setter
    def output_dir(self, dir: PathLike) -> None:
        self.set_output_dir(dir)

    def set_output_dir(self, dir: PathLike, force: bool = False) -> None:
        """Sets the output directory (:attr:`output_dir`), claiming it as ``haff run --out``.

        A new or empty directory, or one holding this run's outputs, gets the manifest
        ``haff-run.json``; another run's outputs are replaced only with `force`; a
        directory holding other files is refused.

        Parameters
        ----------
        dir : str or path
            The directory (made if missing).
        force : bool, default False
            Replace another run's outputs (``haff run --force``).

        Returns
        -------
        None

        Raises
        ------
        ConfigError
            A directory holding another run's outputs (without `force`) or other files.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas)
        >>> sim.set_output_dir("claimed")
        >>> import os; sorted(os.listdir("claimed"))
        ['haff-run.json']
        """
        if dir is None or not isinstance(dir, (str, os.PathLike)):
            raise ConfigError(
                f"output_dir: a directory (str or path), not {type(dir).__name__}")
        self._sim.set_output_dir(os.fspath(dir), bool(force))

    def _check_output_dir(self) -> None:
        """Refuses a run that writes files during the run without an output directory."""
        if self._sim.output_dir is not None:
            return
        output = self.config.get("output") or {}
        for key, files in _FILE_OUTPUTS:
            if output.get(key) is not None:
                raise ConfigError(
                    f"output.{key}: writes {files} files during the run: give the simulation "
                    "an output directory, haff.Simulation(config, output_dir=DIR) or "
                    "sim.output_dir = DIR")

    def run(self, progress: Optional[bool] = None) -> Simulation:
        """Runs to the end, taking the samples of ``run.samples``.

        The end is ``run.end_time`` or ``run.collisions_per_particle``; a run that was
        stopped (by :meth:`advance`, Ctrl-C or a check-point) goes on from where it
        stands. The GIL is released while the run goes on.

        Parameters
        ----------
        progress : bool or None, default None
            A progress bar over the samples (tqdm's, in a notebook or a terminal, if tqdm
            is installed; else a line on stderr) when True, none when False; None: a bar
            when the session is interactive (a notebook, or stderr a terminal).

        Returns
        -------
        Simulation
            The simulation itself (so that ``haff.Simulation(config).run()`` chains).

        Raises
        ------
        ConfigError
            Fields or snapshots asked for without an :attr:`output_dir`.
        KeyboardInterrupt
            Ctrl-C: the run stops between pieces, ready to go on.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas).run(progress=False)
        >>> sim.complete, sim.collisions_per_particle
        (True, 10.0)
        """
        self._check_output_dir()
        self._sim.run(progress_callback(progress))
        return self

    def advance(self, time: Optional[float] = None,
                collisions_per_particle: Optional[float] = None,
                progress: Optional[bool] = False) -> bool:
        """Runs part of the run: to `time` or to `collisions_per_particle` (exactly one).

        The samples of the schedule on the way are taken. Stopping between samples and
        going on changes nothing for event-driven runs (bit for bit); a DSMC run stopped
        at a time shortens one step to end there.

        Parameters
        ----------
        time : float, optional
            The time to stop at, in the run's unit of time; between where the run stands
            and its end (a run stopped by collisions may be given a time beyond its end:
            it ends first).
        collisions_per_particle : float, optional
            The collisions per particle to stop at (2 x collisions / N), within the run.
        progress : bool or None, default False
            As for :meth:`run`.

        Returns
        -------
        bool
            True if the run stands at that point, False if it ended before it.

        Raises
        ------
        ConfigError
            Neither or both given, or a point outside the run.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas)
        >>> sim.advance(time=1.0), sim.time, len(sim.timeseries["time"])
        (True, 1.0, 4)
        >>> sim.advance(collisions_per_particle=5.0), sim.collisions_per_particle
        (True, 5.0)
        """
        self._check_output_dir()
        return self._sim.advance(time, collisions_per_particle, progress_callback(progress))

    @property
    def timeseries(self) -> Dict[str, Floats]:
        """The samples so far: column name -> array, the columns of ``timeseries.csv``.

        ``time``, ``collisions_per_particle``, ``temperature`` (T = sum m c^2 / (N D)
        of the peculiar velocities c), ``a2`` (the Sonine coefficient of the velocity
        distribution, <c^4> / <c^4>_Maxwell - 1), ``energy_lost`` (dissipated since the
        start), ``pressure``, ``events``; ``bath_temperature`` with a stochastic law;
        ``rotational_temperature`` for rough particles (``collision.tangential_restitution``
        > -1). One value per sample (a copy), equal to the file's bit for bit.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> ts = haff.Simulation(gas).run(progress=False).timeseries
        >>> list(ts)
        ['time', 'collisions_per_particle', 'temperature', 'a2', 'energy_lost', 'pressure', 'events']
        >>> ts["collisions_per_particle"]
        array([ 0.   ,  0.012,  0.056,  0.316,  1.78 , 10.   ])
        """
        return self._sim.timeseries()

    @property
    def species_timeseries(self) -> Optional[Dict[str, Floats]]:
        """The per-species samples of a mixture (``system.species``), or None.

        Column name -> array, the columns of ``species.csv``: ``time``,
        ``collisions_per_particle``, ``species`` (the index in ``system.species``),
        ``temperature``, ``a2``, ``collision_frequency`` (collisions per particle of the
        species per unit time since the previous sample; NaN where it is not measured:
        the first sample, soft-sphere runs); one row per species and sample. None for a
        run without ``system.species``.

        Examples
        --------
        >>> import haff
        >>> mixture = {"system": {"particles": 400, "packing_fraction": 0.1, "seed": 1,
        ...                       "species": [
        ...                           {"diameter": 1.0, "mass": 1.0, "fraction": 0.5},
        ...                           {"diameter": 2.0, "mass": 8.0, "fraction": 0.5}]},
        ...            "collision": {"law": "constant", "restitution": 0.9},
        ...            "run": {"collisions_per_particle": 5, "samples": 3}}
        >>> rows = haff.Simulation(mixture).run(progress=False).species_timeseries
        >>> rows["species"], rows["temperature"].round(3)
        (array([0, 1, 0, 1, 0, 1]), array([1.006, 0.994, 1.004, 0.996, 0.645, 0.798]))
        """
        return self._sim.species_timeseries()

    def walls(self) -> Optional[pandas.DataFrame]:
        """What the walls of a container (``[[wall]]``) have done, as ``walls.csv``.

        Returns
        -------
        pandas.DataFrame or None
            The columns of ``walls.csv``: ``time``, ``collisions_per_particle``, ``axis``,
            ``side``, ``collisions``, ``momentum`` (given to the wall), ``energy`` (given
            to the gas by a thermal wall); one row per wall and sample, cumulative from
            the start. None for a run in the periodic box.

        Raises
        ------
        ImportError
            pandas is not installed.

        Examples
        --------
        >>> import haff
        >>> box = {"system": {"dimension": 2, "particles": 200, "packing_fraction": 0.1,
        ...                   "seed": 7},
        ...        "collision": {"law": "constant", "restitution": 1.0},
        ...        "run": {"collisions_per_particle": 10.0, "samples": 4},
        ...        "wall": [{"axis": "y", "side": "low", "kind": "thermal", "temperature": 2.0},
        ...                 {"axis": "y", "side": "high", "kind": "elastic"}]}
        >>> walls = haff.Simulation(box).run(progress=False).walls()
        >>> walls[["axis", "side", "collisions", "energy"]].tail(2).round(2)
          axis  side  collisions  energy
        6    y   low          45   73.91
        7    y  high          55    0.00
        """
        columns = self._sim.walls()
        if columns is None:
            return None
        try:
            import pandas
        except ImportError:  # pragma: no cover - depends on the environment
            raise ImportError("walls needs pandas: pip install pandas") from None
        order = ["time", "collisions_per_particle", "axis", "side", "collisions", "momentum",
                 "energy"]
        return pandas.DataFrame({name: columns[name] for name in order})

    def pressure(self) -> Optional[pandas.DataFrame]:
        """The pressure tensor at every sample, as ``pressure.csv``.

        Recorded with ``[output] pressure = true``, and always with ``[shear]``: the
        kinetic part of the velocities relative to the flow plus the collisional part
        averaged since the previous sample.

        Returns
        -------
        pandas.DataFrame or None
            The columns of ``pressure.csv``: ``time``, ``collisions_per_particle``,
            ``pxx``, ``pyy``, ``pzz``, ``pxy``, ``pxz``, ``pyz``, ``kinetic_xy`` (the run's
            units: energy per volume, or per area in 2D). None without them.

        Raises
        ------
        ImportError
            pandas is not installed.

        Examples
        --------
        >>> import haff
        >>> sheared = {"system": {"dimension": 2, "particles": 400, "packing_fraction": 0.05,
        ...                       "seed": 4},
        ...            "collision": {"law": "constant", "restitution": 0.8},
        ...            "run": {"collisions_per_particle": 40.0, "samples": 20,
        ...                    "spacing": "linear"},
        ...            "shear": {"rate": 0.05}}
        >>> p = haff.Simulation(sheared).run(progress=False).pressure()
        >>> list(p.columns)
        ['time', 'collisions_per_particle', 'pxx', 'pyy', 'pzz', 'pxy', 'pxz', 'pyz', 'kinetic_xy']
        >>> bool((p["pxy"].iloc[10:] < 0).all())   # the shear stress opposes the shear
        True
        """
        columns = self._sim.pressure()
        if columns is None:
            return None
        try:
            import pandas
        except ImportError:  # pragma: no cover - depends on the environment
            raise ImportError("pressure needs pandas: pip install pandas") from None
        order = ["time", "collisions_per_particle", "pxx", "pyy", "pzz", "pxy", "pxz", "pyz",
                 "kinetic_xy"]
        return pandas.DataFrame({name: columns[name] for name in order})

    def rheology(self) -> Optional[Dict[str, Any]]:
        """The rheology of a sheared run (``[shear]``), as ``summary.json`` has it.

        Returns
        -------
        dict or None
            Over the second half of the samples so far: ``temperature``, the pressure
            tensor over n T (``pxx``, ``pyy``, ``pzz``, ``pxy``), the shear ``viscosity``
            -P_xy / a, its ``reduced_viscosity``, the ``reduced_shear_rate`` and the
            normal stress differences, each a dict of ``mean`` and ``error`` (batch
            means); ``from_time``, ``to_time``, ``samples``, ``shear_rate``; Grad's steady
            state under ``theory`` where it applies. None without ``[shear]``.

        Examples
        --------
        >>> import haff
        >>> sheared = {"system": {"dimension": 2, "particles": 400, "packing_fraction": 0.05,
        ...                       "seed": 4},
        ...            "collision": {"law": "constant", "restitution": 0.8},
        ...            "run": {"collisions_per_particle": 40.0, "samples": 20,
        ...                    "spacing": "linear"},
        ...            "shear": {"rate": 0.05}}
        >>> r = haff.Simulation(sheared).run(progress=False).rheology()
        >>> round(r["reduced_viscosity"]["mean"], 2), round(r["reduced_viscosity"]["error"], 2)
        (0.79, 0.03)
        >>> round(r["theory"]["reduced_viscosity"], 2)   # Grad's 13 moments
        0.8
        """
        text = self._sim.rheology()
        return None if text is None else _json(text)

    def green_kubo(self) -> Optional[Dict[str, Any]]:
        """The shear viscosity of an elastic gas at equilibrium by Green-Kubo.

        Einstein-Helfand from the fluctuations of the pressure tensor
        (``output.pressure`` without ``[shear]``), as ``summary.json``'s ``green_kubo``
        has it.

        Returns
        -------
        dict or None
            ``viscosity`` and ``reduced_viscosity`` (over eta0 at the measured
            temperature), each a dict of ``mean`` and ``error``, the fit window and
            Enskog's value under ``theory``; or ``{"skipped": reason}`` for a run that is
            not at equilibrium or too short (at least 200 mean free times). None without
            ``output.pressure`` or under ``[shear]``.

        Examples
        --------
        >>> import haff
        >>> elastic = {"system": {"particles": 300, "packing_fraction": 0.1, "seed": 2},
        ...            "collision": {"law": "constant", "restitution": 1.0},
        ...            "run": {"end_time": 20.0, "samples": 200, "spacing": "linear"},
        ...            "output": {"pressure": True}}
        >>> haff.Simulation(elastic).run(progress=False).green_kubo()
        {'skipped': 'the run is 35.40... mean free times long: at least 200 for 5 batches'}
        """
        text = self._sim.green_kubo()
        return None if text is None else _json(text)

    def profiles(self) -> Optional[pandas.DataFrame]:
        """Profiles along an axis (``[output] profiles = {axis, bins}``), as ``profiles.csv``.

        Returns
        -------
        pandas.DataFrame or None
            The columns of ``profiles.csv``: ``time``, ``collisions_per_particle``,
            ``position`` (the slab's centre), ``density`` (number per volume),
            ``packing_fraction``, ``temperature``, ``temperature_x/y/z``,
            ``velocity_x/y/z``; one row per slab and sample; NaN where the CSV cell is
            empty (components a dimension lacks, the velocity of an empty slab,
            temperatures below two particles). None without ``output.profiles``.

        Raises
        ------
        ImportError
            pandas is not installed.

        Examples
        --------
        A thermal wall at y = 0 heats a gas of elastic disks:

        >>> import haff
        >>> box = {"system": {"dimension": 2, "particles": 200, "packing_fraction": 0.1,
        ...                   "seed": 7},
        ...        "collision": {"law": "constant", "restitution": 1.0},
        ...        "run": {"collisions_per_particle": 10.0, "samples": 4},
        ...        "wall": [{"axis": "y", "side": "low", "kind": "thermal", "temperature": 2.0},
        ...                 {"axis": "y", "side": "high", "kind": "elastic"}],
        ...        "output": {"profiles": {"axis": "y", "bins": 4}}}
        >>> p = haff.Simulation(box).run(progress=False).profiles()
        >>> p[["position", "density", "temperature"]].tail(4).round(2)
            position  density  temperature
        12      4.95     0.10         2.16
        13     14.86     0.12         1.34
        14     24.77     0.13         1.02
        15     34.68     0.15         1.15
        """
        columns = self._sim.profiles()
        if columns is None:
            return None
        try:
            import pandas
        except ImportError:  # pragma: no cover - depends on the environment
            raise ImportError("profiles needs pandas: pip install pandas") from None
        order = ["time", "collisions_per_particle", "position", "density", "packing_fraction",
                 "temperature", "temperature_x", "temperature_y", "temperature_z",
                 "velocity_x", "velocity_y", "velocity_z"]
        return pandas.DataFrame({name: columns[name] for name in order})

    def timeseries_frame(self) -> pandas.DataFrame:
        """The time series (:attr:`timeseries`) as a pandas DataFrame.

        Returns
        -------
        pandas.DataFrame
            A row per sample, the columns of ``timeseries.csv``.

        Raises
        ------
        ImportError
            pandas is not installed.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> frame = haff.Simulation(gas).run(progress=False).timeseries_frame()
        >>> frame[["collisions_per_particle", "temperature", "a2"]].round(3)
           collisions_per_particle  temperature     a2
        0                    0.000        1.000 -0.036
        1                    0.012        0.999 -0.038
        2                    0.056        0.996 -0.044
        3                    0.316        0.982 -0.050
        4                    1.780        0.890 -0.056
        5                   10.000        0.533 -0.004
        """
        try:
            import pandas
        except ImportError:  # pragma: no cover - depends on the environment
            raise ImportError("timeseries_frame needs pandas: pip install pandas") from None
        return pandas.DataFrame(self.timeseries)

    @property
    def velocity_histograms(self) -> List[Dict[str, Any]]:
        """The velocity histograms taken at ``run.histogram_at``, as
        ``velocity_histograms.csv``.

        A list of dicts, one per histogram: ``target`` (the value of
        ``run.histogram_at``), ``time``, ``collisions_per_particle``, ``c`` (bin centres
        of the scaled velocity component c = v / sqrt(2 T / m)), ``density`` (normalized
        to 1 over c) and ``maxwellian`` (exp(-c^2) / sqrt(pi)). Empty without
        ``run.histogram_at``.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6,
        ...                "histogram_at": [0.0, 10.0]}}
        >>> h = haff.Simulation(gas).run(progress=False).velocity_histograms
        >>> [(x["target"], x["c"].size) for x in h]
        [(0.0, 60), (10.0, 60)]
        """
        out = []
        for target, time, cpp, c, density in self._sim.velocity_histograms():
            out.append({"target": target, "time": time, "collisions_per_particle": cpp,
                        "c": c, "density": density,
                        "maxwellian": np.exp(-c * c) / math.sqrt(math.pi)})
        return out

    def modes(self) -> Dict[str, Floats]:
        """The hydrodynamic modes recorded so far (``output.modes``), as ``modes.csv``.

        Returns
        -------
        dict of numpy.ndarray
            Column name -> array, the columns and rows of ``modes.csv``: ``time``,
            ``collisions_per_particle``, ``k`` (the wave number 2 pi |n| / L),
            ``transverse_energy``, ``longitudinal_energy``, ``density_power``; one row per
            sample and shell of wave vectors |n|^2 = 1 .. ``output.mode_shells``, empty
            shells left out. Energies are normalized by a homogeneous gas at the current
            temperature (1 for a homogeneous gas). Empty arrays without ``output.modes``.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6},
        ...        "output": {"modes": True, "mode_shells": 2}}
        >>> m = haff.Simulation(gas).run(progress=False).modes()
        >>> m["k"][-2:].round(4), m["transverse_energy"][-2:].round(3)
        (array([0.4559, 0.6447]), array([0.895, 0.704]))
        """
        return self._sim.modes()

    def structure(self) -> Dict[str, npt.NDArray[Any]]:
        """S(k) and g(r) recorded so far (``output.structure``), as ``structure.csv``.

        Returns
        -------
        dict of numpy.ndarray
            Column name -> array, the columns and rows of ``structure.csv``: ``time``,
            ``collisions_per_particle``, ``function``, ``x``, ``value``. ``function`` is a
            string array, ``"S"`` (x = k, the static structure factor) or ``"g"`` (x = r,
            the pair correlation function); select with ``s["function"] == "S"``. Per
            sample the S(k) rows come first, then g(r).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6},
        ...        "output": {"structure": True}}
        >>> s = haff.Simulation(gas).run(progress=False).structure()
        >>> last = s["time"] == s["time"][-1]
        >>> g = last & (s["function"] == "g")
        >>> s["x"][g][:3], s["value"][g][:3]     # no pairs closer than a diameter
        (array([0.025, 0.075, 0.125]), array([0., 0., 0.]))
        """
        time, cpp, function, x, value = self._sim.structure()
        return {"time": time, "collisions_per_particle": cpp,
                "function": np.array(function, dtype="<U1"), "x": x, "value": value}

    def _files(self, records: List[Tuple[float, str]]) -> List[Tuple[float, Path]]:
        dir = self.output_dir
        return [(time, Path(name) if dir is None else dir / name) for time, name in records]

    def field_files(self) -> List[Tuple[float, Path]]:
        """(time, path) of the field files written so far (``output.fields``).

        VTK image data (``fields_NNNNNN.vti``: the cell data density, velocity,
        temperature and vorticity on the grid) in :attr:`output_dir`, for ParaView.

        Returns
        -------
        list of (float, pathlib.Path)
            The time and the path of each file, in order (file names only while no
            output directory is set, e.g. after :meth:`load`).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6},
        ...        "output": {"fields": {"every": 2, "grid": 8}}}
        >>> sim = haff.Simulation(gas, output_dir="fields").run(progress=False)
        >>> [path.name for time, path in sim.field_files()]
        ['fields_000000.vti', 'fields_000002.vti', 'fields_000004.vti']
        """
        return self._files(self._sim.field_files())

    def snapshot_files(self) -> List[Tuple[float, Path]]:
        """(time, path) of the snapshots written so far (``output.snapshots``).

        VTK unstructured grids (``snapshot_NNNNNN.vtu``: the particles as points with the
        point data radius, mass, velocity, species, collisions (event-driven) and
        bath_temperature (stochastic law), the box as field data). Without ``"vtk"``
        among the formats, the trajectory holding each snapshot (``snapshots.lammpstrj``
        or ``snapshots.xyz``, a frame per snapshot, in order: read frame k with
        ``haff.read_configuration(path, format, frame=k)``).

        Returns
        -------
        list of (float, pathlib.Path)
            As :meth:`field_files`.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6},
        ...        "output": {"snapshots": {"every": 5, "format": "xyz"}}}
        >>> sim = haff.Simulation(gas, output_dir="snapshots").run(progress=False)
        >>> [(round(t, 3), str(path)) for t, path in sim.snapshot_files()]
        [(0.0, 'snapshots/snapshots.xyz'), (6.731, 'snapshots/snapshots.xyz')]
        >>> haff.read_configuration("snapshots/snapshots.xyz", "xyz", frame=1)["positions"].shape
        (500, 3)
        """
        return self._files(self._sim.snapshot_files())

    @property
    def positions(self) -> Floats:
        """Positions now, an (N, D) array (a copy), in the box [0, L)^D.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).positions.shape
        (500, 3)
        """
        return self._sim.particles()[0]

    @property
    def velocities(self) -> Floats:
        """Velocities now, an (N, D) array (a copy).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> v = haff.Simulation(gas).velocities
        >>> v.shape, bool(abs(v.sum(axis=0)).max() < 1e-9)   # zero total momentum
        ((500, 3), True)
        """
        return self._sim.particles()[1]

    @property
    def radii(self) -> Floats:
        """The particles' radii, an (N,) array (a copy).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).radii[:3]       # diameter 1 by default
        array([0.5, 0.5, 0.5])
        """
        return self._sim.particles()[2]

    @property
    def masses(self) -> Floats:
        """The particles' masses, an (N,) array (a copy).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).masses[:3]      # mass 1 by default
        array([1., 1., 1.])
        """
        return self._sim.particles()[3]

    @property
    def time(self) -> float:
        """The time of the run now, in the run's unit of time (0 at the start).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> round(haff.Simulation(gas).run(progress=False).time, 4)
        6.7312
        """
        return self._sim.time

    @property
    def temperature(self) -> float:
        """The granular temperature now, T = sum m c^2 / (N D) of the peculiar velocities.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas)
        >>> round(sim.temperature, 6)                # system.temperature, exactly
        1.0
        >>> round(sim.run(progress=False).temperature, 4)
        0.5328
        """
        return self._sim.temperature()

    @property
    def collisions(self) -> int:
        """Collisions so far (DSMC: accepted candidates).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).run(progress=False).collisions   # 10 x 500 / 2
        2500
        """
        return self._sim.counters()[0]

    @property
    def events(self) -> int:
        """Events so far (event-driven: collisions, cell crossings, stale predictions).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).run(progress=False).events
        9406
        """
        return self._sim.counters()[1]

    @property
    def collisions_per_particle(self) -> float:
        """Collisions per particle so far, 2 x :attr:`collisions` / N.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).run(progress=False).collisions_per_particle
        10.0
        """
        return 2.0 * self.collisions / self._sim.particle_count

    @property
    def energy_lost(self) -> float:
        """Kinetic energy dissipated by collisions since the start (the run's energy unit).

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas).run(progress=False)
        >>> round(sim.energy_lost, 2)       # = N D (T0 - T) / 2 = 750 (1 - 0.5328)
        350.38
        """
        return self._sim.counters()[2]

    def contact_statistics(self) -> Optional[Dict[str, float]]:
        """The contacts of a soft-sphere run so far, the ``contacts`` of ``summary.json``.

        Returns
        -------
        dict or None
            ``time_step``, ``steps``, ``contacts_now`` (pairs overlapping now),
            ``elastic_energy`` (held in those overlaps, sum of (2/5) rho xi^(5/2); the
            kinetic temperature leaves it out), ``max_relative_overlap`` (the largest
            overlap over the contact distance), ``contact_steps`` and
            ``multi_contact_steps`` (particle-steps touching one or more / two or more
            others) and ``multi_contact_fraction`` (their ratio), ``eps_error`` (how well
            the time step resolves a contact: the largest |eps(MD) - eps(exact law)| of
            isolated head-on contacts at 0.1, 1 and 10 initial thermal speeds). None for
            the other engines (``run.engine`` other than ``"soft-sphere"``).

        Examples
        --------
        >>> import haff
        >>> soft = {"system": {"particles": 300, "packing_fraction": 0.05, "seed": 2},
        ...         "collision": {"law": "viscoelastic", "young": 1e5, "poisson": 0.3,
        ...                       "dissipative_constant": 0.01},
        ...         "run": {"engine": "soft-sphere", "end_time": 1.0, "samples": 3}}
        >>> c = haff.Simulation(soft).run(progress=False).contact_statistics()
        >>> c["steps"], round(c["max_relative_overlap"], 4), round(c["eps_error"], 5)
        (2859, 0.0255, 0.00058)
        """
        return self._sim.contact_statistics()

    @property
    def initial_state(self) -> Optional[Dict[str, Any]]:
        """How a dense start was made, the ``initial_state`` of ``summary.json``, or None.

        Above the lattice limit (phi 0.45 in 3D, 0.7 in 2D) the spheres are grown by
        event-driven MD (Lubachevsky-Stillinger) from ``start_fraction``; ``method``
        ("growth"), ``collisions``, ``events`` and ``seconds`` give its cost. None for the
        other starts.

        Examples
        --------
        >>> import haff
        >>> dense = {"system": {"particles": 200, "packing_fraction": 0.5, "seed": 2},
        ...          "collision": {"law": "constant", "restitution": 0.9},
        ...          "run": {"collisions_per_particle": 1.0, "samples": 2}}
        >>> state = haff.Simulation(dense).initial_state
        >>> state["method"], state["start_fraction"]
        ('growth', 0.3)
        """
        raw = self._sim.initial_state_json()
        return None if raw is None else _json(raw)

    @property
    def complete(self) -> bool:
        """Whether every sample of the run has been taken.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas)
        >>> sim.complete, sim.run(progress=False).complete
        (False, True)
        """
        return self._sim.complete

    @property
    def config(self) -> Dict[str, Any]:
        """The run description, normalized (every default filled in), as a dict.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> c = haff.Simulation(gas).config
        >>> c["system"]["dimension"], c["system"]["temperature"], c["run"]["engine"]
        (3, 1.0, 'event-driven')
        """
        return _json(self._sim.description_json())

    @property
    def wall_seconds(self) -> float:
        """Wall-clock seconds spent building and running in this process.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).run(progress=False).wall_seconds > 0
        True
        """
        return self._sim.wall_seconds

    def save(self, path: PathLike) -> None:
        """Writes a check-point from which :meth:`load` goes on bit for bit.

        Event-driven particles are brought to the present first, as
        ``haff run --checkpoint-every`` does; the saved and the continued run then agree
        with each other bit for bit. ``haff run --resume DIR`` continues from it too.

        Parameters
        ----------
        path : str or path
            A file, or a directory (``checkpoint.bin`` in it).

        Returns
        -------
        None

        Raises
        ------
        OSError
            The file cannot be written.

        Examples
        --------
        >>> import haff
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> sim = haff.Simulation(gas)
        >>> sim.advance(time=1.0)
        True
        >>> sim.save("state.bin")
        >>> haff.Simulation.load("state.bin").time
        1.0
        """
        self._sim.save(os.fspath(path))

    def write(self, dir: Optional[PathLike] = None, force: bool = False) -> None:
        """Writes the files ``haff run --out DIR`` writes.

        ``haff-run.json``, ``timeseries.csv``, ``velocity_histograms.csv`` (with
        ``run.histogram_at``), ``temperature.png``, ``summary.json`` and, as the run asks
        for them, ``species.csv``, ``walls.csv``, ``pressure.csv``, ``profiles.csv``,
        ``modes.csv``, ``structure.csv``, ``fields.pvd`` and ``snapshots.pvd`` (the
        ParaView collections name the files written during the run by file name, so
        they belong in the output directory). Writing the same run again updates them.

        Parameters
        ----------
        dir : str or path, optional
            The directory (made if missing); default: :attr:`output_dir`.
        force : bool, default False
            Replace another run's outputs in `dir`.

        Returns
        -------
        None

        Raises
        ------
        ConfigError
            No `dir` and no :attr:`output_dir`; a directory holding another run's outputs
            (without `force`) or other files.

        Examples
        --------
        >>> import haff, os
        >>> gas = {"system": {"particles": 500, "packing_fraction": 0.1, "seed": 1},
        ...        "collision": {"law": "constant", "restitution": 0.9},
        ...        "run": {"collisions_per_particle": 10, "samples": 6}}
        >>> haff.Simulation(gas).run(progress=False).write("out")
        >>> sorted(os.listdir("out"))
        ['haff-run.json', 'summary.json', 'temperature.png', 'timeseries.csv']
        """
        if dir is None:
            dir = self.output_dir
            if dir is None:
                raise ConfigError("dir: give a directory (no output_dir is set)")
        Path(dir).mkdir(parents=True, exist_ok=True)
        self._sim.write(os.fspath(dir), bool(force))

    def __repr__(self) -> str:
        c = self.config
        return (f"<haff.Simulation {c['system']['dimension']}D N={c['system']['particles']} "
                f"engine={c['run'].get('engine', 'event-driven')} t={self.time:.6g} "
                f"samples={len(self.timeseries['time'])} complete={self.complete}>")
