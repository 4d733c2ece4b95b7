"""Granular-gas runs from Python, on the library run driver that ``haff run`` drives."""

from __future__ import annotations

import json
import math
import os
import sys
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np

from . import _haff
from ._haff import ConfigError
from ._progress import progress_callback

Config = Union[Mapping[str, Any], str, "os.PathLike[str]"]
PathLike = Union[str, "os.PathLike[str]"]

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
    """A dict with the run file's structure as TOML text (sections as tables)."""
    lines: List[str] = []
    for section, body in config.items():
        if not isinstance(body, Mapping):
            lines.insert(0, f"{_toml_key(section)} = {_toml_value(body, str(section))}")
            continue
        lines.append(f"[{_toml_key(section)}]")
        for key, value in body.items():
            lines.append(f"{_toml_key(key)} = {_toml_value(value, f'{section}.{key}')}")
    return "\n".join(lines) + "\n"


def _build(config: Config, initial: Optional[Mapping[str, Any]] = None) -> "_haff._Simulation":
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


def _build_with_initial(config: Config, initial: Mapping[str, Any]) -> "_haff._Simulation":
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
    """A granular-gas run: event-driven MD or DSMC, as ``haff run`` runs it.

    Parameters
    ----------
    config : dict, str or path
        The run file's structure as a dict (``{"system": {...}, "collision": {...},
        "run": {...}}``), a path to a TOML run file, or TOML text. Every key, default and
        check is that of ``haff run`` (see the README); a bad value raises
        :class:`haff.ConfigError` naming the key, e.g. ``system.packing_fraction``.
    output_dir : str or path, optional
        The output directory, as ``haff run --out DIR``: the field and snapshot files of
        ``[output]`` are written there during the run (see :attr:`output_dir`), and
        :meth:`write` writes there by default.
    force : bool
        Replace another run's outputs in `output_dir` (``haff run --force``).
    initial : dict of arrays, optional
        The particles to start from instead of a placement, as
        :func:`haff.read_configuration` returns them: ``positions`` (N, D) and any of
        ``box`` (D sides; else ``system.box``), ``velocities`` (N, D; else drawn at
        ``system.temperature``), ``diameters`` (N,), ``masses`` (N,), ``species`` (N,),
        ``spins`` (N, 3); a ``time`` is ignored (the run starts at 0). Checked as a particle file (``system.initial``): overlapping
        spheres, particles outside the box and non-finite values raise
        :class:`haff.ConfigError` naming the record; ``system.particles``,
        ``packing_fraction`` and ``species`` are refused (the arrays make them).

        Example::

            c = haff.read_configuration("packing.xyz", "xyz")
            sim = haff.Simulation({"system": {"dimension": 3}, "collision": {...},
                                   "run": {...}}, initial=c)

    The same description and seed give the same numbers as ``haff run``, bit for bit.
    Runs go on with the GIL released; Ctrl-C interrupts them between pieces (about
    0.1 s), leaving the run where it stopped, ready to go on.
    """

    def __init__(self, config: Config, output_dir: Optional[PathLike] = None,
                 force: bool = False, initial: Optional[Mapping[str, Any]] = None):
        self._sim = _build(config, initial)
        if output_dir is not None:
            self.set_output_dir(output_dir, force=force)

    @classmethod
    def load(cls, path: PathLike, output_dir: Optional[PathLike] = None,
             force: bool = False) -> "Simulation":
        """The run saved by :meth:`save` (a file, or a directory holding
        ``checkpoint.bin``, such as a ``haff run`` output directory), checked as
        ``haff run --resume`` checks it; it continues bit for bit. The output directory
        is not part of a check-point: give `output_dir` again (a ``haff run`` directory
        may be its own) for a run that writes fields or snapshots."""
        self = cls.__new__(cls)
        self._sim = _haff._Simulation.load(os.fspath(path))
        if output_dir is not None:
            self.set_output_dir(output_dir, force=force)
        return self

    @property
    def output_dir(self) -> Optional[Path]:
        """The output directory (None until set): the field files
        (``fields_NNNNNN.vti``) and snapshots (``snapshot_NNNNNN.vtu``) of ``[output]`` are
        written there during the run, NNNNNN the sample number. A run asking for them
        without one raises :class:`haff.ConfigError` naming ``output.fields`` or
        ``output.snapshots`` before it starts. Setting it claims the directory as
        ``haff run --out`` does (:meth:`set_output_dir`)."""
        path = self._sim.output_dir
        return None if path is None else Path(path)

    @output_dir.setter
    def output_dir(self, dir: PathLike) -> None:
        self.set_output_dir(dir)

    def set_output_dir(self, dir: PathLike, force: bool = False) -> None:
        """Sets the output directory (:attr:`output_dir`), claiming it as
        ``haff run --out DIR`` does: a new or empty directory, or one holding this run's
        outputs, gets the manifest ``haff-run.json``; another run's outputs are replaced
        only with `force`; a directory holding other files is refused."""
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

    def run(self, progress: Optional[bool] = None) -> "Simulation":
        """Runs to the end of the run (``run.end_time`` or ``run.collisions_per_particle``),
        taking the samples of ``run.samples``.

        progress: a progress bar (tqdm's, in a notebook or terminal, if tqdm is installed;
        else a line on stderr) when True, or when None and the session is interactive.
        Returns the simulation itself.
        """
        self._check_output_dir()
        self._sim.run(progress_callback(progress))
        return self

    def advance(self, time: Optional[float] = None,
                collisions_per_particle: Optional[float] = None,
                progress: Optional[bool] = False) -> bool:
        """Runs part of the run: to `time` or to `collisions_per_particle` (exactly one),
        taking the samples of the schedule on the way. Returns True if the run stands at
        that point, False if the run ended before it. A point in the unit of the run's stop
        criterion must lie between where the run stands and its end.

        Stopping between samples and going on changes nothing for event-driven runs (bit
        for bit); a DSMC run stopped at a time shortens one step to end there.
        """
        self._check_output_dir()
        return self._sim.advance(time, collisions_per_particle, progress_callback(progress))

    @property
    def timeseries(self) -> Dict[str, np.ndarray]:
        """The samples so far: column name -> array, with the columns of
        ``timeseries.csv`` (time, collisions_per_particle, temperature, a2, energy_lost,
        pressure, events; bath_temperature with a stochastic law; rotational_temperature
        for rough particles, ``collision.tangential_restitution`` > -1)."""
        return self._sim.timeseries()

    @property
    def species_timeseries(self) -> Optional[Dict[str, np.ndarray]]:
        """The per-species samples of a mixture (``system.species``): column name -> array,
        with the columns of ``species.csv`` (time, collisions_per_particle, species,
        temperature, a2, collision_frequency; one row per species and sample, NaN where the
        collision frequency is not measured: the first sample, soft-sphere runs). None for
        a run without ``system.species``."""
        return self._sim.species_timeseries()

    def walls(self):
        """What the walls of a container (``[[wall]]``) have done: a pandas DataFrame with
        the columns of ``walls.csv`` (time, collisions_per_particle, axis, side,
        collisions, momentum, energy; one row per wall and sample, cumulative from the
        start). None for a run in the periodic box. Needs pandas."""
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

    def pressure(self):
        """The pressure tensor at every sample (``[output] pressure = true``, always with
        ``[shear]``): a pandas DataFrame with the columns of ``pressure.csv`` (time,
        collisions_per_particle, pxx, pyy, pzz, pxy, pxz, pyz, kinetic_xy): the kinetic part
        of the velocities relative to the flow plus the collisional part averaged since the
        previous sample. None without them. Needs pandas."""
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
        """The rheology of a sheared run (``[shear]``), as ``summary.json`` has it: over the
        second half of the samples so far, the temperature, the pressure tensor over n T
        (pxx, pyy, pzz, pxy), the shear viscosity -P_xy / a, its reduced value, the reduced
        shear rate and the normal stress differences, each a dict of ``mean`` and ``error``
        (batch means); Grad's steady state under ``theory`` where it applies. None without
        ``[shear]``."""
        text = self._sim.rheology()
        return None if text is None else json.loads(text)

    def green_kubo(self) -> Optional[Dict[str, Any]]:
        """The shear viscosity of an elastic gas at equilibrium by Green-Kubo (Einstein-Helfand)
        from the pressure tensor's fluctuations (``output.pressure`` without ``[shear]``), as
        ``summary.json``'s ``green_kubo`` has it: ``viscosity`` and ``reduced_viscosity``
        (over eta0 at the measured temperature), each a dict of ``mean`` and ``error``, the
        fit window and Enskog's value under ``theory``; or ``{"skipped": reason}`` for a run
        that is not at equilibrium or too short. None without ``output.pressure`` or under
        ``[shear]``."""
        text = self._sim.green_kubo()
        return None if text is None else json.loads(text)

    def profiles(self):
        """Profiles along an axis (``[output] profiles = {axis, bins}``): a pandas DataFrame
        with the columns of ``profiles.csv`` (time, collisions_per_particle, position,
        density, packing_fraction, temperature, temperature_x/y/z, velocity_x/y/z; one row
        per slab and sample; NaN where the CSV cell is empty: components a dimension lacks,
        the velocity of an empty slab, temperatures below two particles). None without
        ``output.profiles``. Needs pandas."""
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

    def timeseries_frame(self):
        """The time series as a pandas DataFrame (needs pandas)."""
        try:
            import pandas
        except ImportError:  # pragma: no cover - depends on the environment
            raise ImportError("timeseries_frame needs pandas: pip install pandas") from None
        return pandas.DataFrame(self.timeseries)

    @property
    def velocity_histograms(self) -> List[Dict[str, Any]]:
        """The velocity histograms taken at ``run.histogram_at``: dicts with ``target``,
        ``time``, ``collisions_per_particle``, ``c`` (bin centres of the scaled velocity
        component c = v / sqrt(2 T / m)), ``density`` and ``maxwellian``
        (exp(-c^2) / sqrt(pi)), as the rows of ``velocity_histograms.csv``."""
        out = []
        for target, time, cpp, c, density in self._sim.velocity_histograms():
            out.append({"target": target, "time": time, "collisions_per_particle": cpp,
                        "c": c, "density": density,
                        "maxwellian": np.exp(-c * c) / math.sqrt(math.pi)})
        return out

    def modes(self) -> Dict[str, np.ndarray]:
        """The hydrodynamic modes recorded so far (``output.modes``): column name -> array,
        the columns and rows of ``modes.csv`` (time, collisions_per_particle, k,
        transverse_energy, longitudinal_energy, density_power; one row per sample and
        shell of wave vectors |n|^2 = 1 .. ``output.mode_shells``, empty shells left out).
        Energies are normalized by a homogeneous gas at the current temperature. Empty
        arrays without ``output.modes``."""
        return self._sim.modes()

    def structure(self) -> Dict[str, np.ndarray]:
        """S(k) and g(r) recorded so far (``output.structure``): column name -> array, the
        columns and rows of ``structure.csv`` (time, collisions_per_particle, function, x,
        value). ``function`` is a string array, ``"S"`` (x = k) or ``"g"`` (x = r); select
        with ``s["function"] == "S"``. Per sample the S(k) rows come first, then g(r)."""
        time, cpp, function, x, value = self._sim.structure()
        return {"time": time, "collisions_per_particle": cpp,
                "function": np.array(function, dtype="<U1"), "x": x, "value": value}

    def _files(self, records: List[Tuple[float, str]]) -> List[Tuple[float, Path]]:
        dir = self.output_dir
        return [(time, Path(name) if dir is None else dir / name) for time, name in records]

    def field_files(self) -> List[Tuple[float, Path]]:
        """(time, path) of the field files written so far (``output.fields``), VTK image
        data (``fields_NNNNNN.vti``, the cell data density, velocity, temperature and
        vorticity on the grid) in :attr:`output_dir` (file names only while no output
        directory is set, e.g. after :meth:`load`)."""
        return self._files(self._sim.field_files())

    def snapshot_files(self) -> List[Tuple[float, Path]]:
        """(time, path) of the snapshots written so far (``output.snapshots``), VTK
        unstructured grids (``snapshot_NNNNNN.vtu``: the particles as points with the point
        data radius, mass, velocity, species, collisions (event-driven) and
        bath_temperature (stochastic law), the box as field data), as :meth:`field_files`.
        Without ``"vtk"`` among the formats, the trajectory holding each snapshot
        (``snapshots.lammpstrj`` or ``snapshots.xyz``, a frame per snapshot, in order:
        ``haff.read_configuration(path, format, frame=k)``)."""
        return self._files(self._sim.snapshot_files())

    @property
    def positions(self) -> np.ndarray:
        """Positions now, an (N, D) array (a copy), in the box [0, L)^D."""
        return self._sim.particles()[0]

    @property
    def velocities(self) -> np.ndarray:
        """Velocities now, an (N, D) array (a copy)."""
        return self._sim.particles()[1]

    @property
    def radii(self) -> np.ndarray:
        return self._sim.particles()[2]

    @property
    def masses(self) -> np.ndarray:
        return self._sim.particles()[3]

    @property
    def time(self) -> float:
        """The time of the run now."""
        return self._sim.time

    @property
    def temperature(self) -> float:
        """The granular temperature now, T = <m c^2> / D."""
        return self._sim.temperature()

    @property
    def collisions(self) -> int:
        """Collisions so far (DSMC: accepted candidates)."""
        return self._sim.counters()[0]

    @property
    def events(self) -> int:
        """Events so far (event-driven: collisions, cell crossings, stale predictions)."""
        return self._sim.counters()[1]

    @property
    def collisions_per_particle(self) -> float:
        return 2.0 * self.collisions / self._sim.particle_count

    @property
    def energy_lost(self) -> float:
        return self._sim.counters()[2]

    def contact_statistics(self) -> Optional[Dict[str, float]]:
        """The contacts of a soft-sphere run so far (``run.engine = "soft-sphere"``), the
        ``contacts`` of summary.json: ``time_step``, ``steps``, ``contacts_now`` (pairs
        overlapping now), ``elastic_energy`` (held in those overlaps, sum of (2/5) rho
        xi^(5/2); the kinetic temperature leaves it out), ``max_relative_overlap`` (largest
        overlap over the contact distance), ``contact_steps`` and ``multi_contact_steps``
        (particle-steps touching one or more / two or more others) and
        ``multi_contact_fraction`` (their ratio), ``eps_error`` (how well the time step
        resolves a contact: the largest |eps(MD) - eps(exact law)| of isolated head-on
        contacts at 0.1, 1 and 10 initial thermal speeds). None for the other engines."""
        return self._sim.contact_statistics()

    @property
    def initial_state(self) -> Optional[Dict[str, Any]]:
        """How a dense start was made, the ``initial_state`` of summary.json: above the
        lattice limit (phi 0.45 in 3D, 0.7 in 2D) the spheres are grown by event-driven MD
        (Lubachevsky-Stillinger) from ``start_fraction``; ``method`` ("growth"),
        ``collisions``, ``events`` and ``seconds`` give its cost. None otherwise."""
        raw = self._sim.initial_state_json()
        return None if raw is None else json.loads(raw)

    @property
    def complete(self) -> bool:
        """Whether every sample of the run has been taken."""
        return self._sim.complete

    @property
    def config(self) -> Dict[str, Any]:
        """The run description, normalized (defaults filled in), as a dict."""
        return json.loads(self._sim.description_json())

    @property
    def wall_seconds(self) -> float:
        """Wall-clock seconds spent building and running in this process."""
        return self._sim.wall_seconds

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes a check-point: the file `path`, or ``checkpoint.bin`` in the directory
        `path`. :meth:`load` continues from it (as does ``haff run --resume DIR``)."""
        self._sim.save(os.fspath(path))

    def write(self, dir: Optional[PathLike] = None, force: bool = False) -> None:
        """Writes the files ``haff run --out DIR`` writes into `dir` (default: the
        :attr:`output_dir`): ``haff-run.json``, ``timeseries.csv``,
        ``velocity_histograms.csv`` (with ``run.histogram_at``), ``temperature.png``,
        ``summary.json`` and, with ``[output]``, ``modes.csv``, ``structure.csv``,
        ``fields.pvd`` and ``snapshots.pvd`` (the ParaView collections name the files
        written during the run by file name, so they belong in the output directory). A
        directory holding another run's outputs is refused unless `force`."""
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
