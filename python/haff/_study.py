"""Studies from Python: ``haff.study``, the same study as ``haff study`` on any executor.

A study is many complete runs of one run file over a grid of parameters and seeds, each in
``output_dir/runs/<point>/<seed>/`` with its manifest and check-points (the layout of the
command). The runs are handed to an executor: threads of this process by default (the runs
release the GIL), a ``concurrent.futures.ProcessPoolExecutor``, or a
``dask.distributed.Client`` (a ``LocalCluster``, or Slurm/PBS through ``dask-jobqueue``).
A worker gets only plain values (the study as TOML text, the directory, the run's index),
writes into the study directory — a file system the workers share — and returns the run's
outcome; the aggregates are computed here, from the runs' files, by the same code as the
command's.
"""

from __future__ import annotations

import concurrent.futures
import json
import operator
import os
import sys
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Union

from . import _haff
from ._haff import ConfigError
from ._progress import _interactive
from ._simulation import _toml_key, _toml_value

PathLike = Union[str, "os.PathLike[str]"]

#: The origin of a study built here (relative paths are made absolute before).
_ORIGIN = "<haff.study>"


def study_toml(base: Union[Mapping[str, Any], PathLike],
               vary: Optional[Mapping[str, Sequence[Any]]] = None,
               seeds: int = 1,
               zip: Optional[Sequence[Mapping[str, Sequence[Any]]]] = None) -> str:
    """The study file (TOML text) of these arguments; a base path is made absolute.

    Parameters
    ----------
    base, vary, seeds, zip
        As for :func:`study`.

    Returns
    -------
    str
        The text of a study file that ``haff study FILE`` runs as :func:`study` would.

    Examples
    --------
    >>> print(study_toml({"run": {"samples": 3}}, {"collision.restitution": [0.7, 0.9]}, 2))
    base = { run = { samples = 3 } }
    seeds = 2
    [vary]
    "collision.restitution" = [0.7, 0.9]
    <BLANKLINE>
    """
    if isinstance(base, Mapping):
        base_line = f"base = {_toml_value(dict(base), 'base')}"
    elif isinstance(base, (str, os.PathLike)):
        path = Path(os.fspath(base))
        if not path.is_file():
            raise ConfigError(f"base: {path}: no such run file (or give the run as a dict)")
        base_line = f"base = {json.dumps(str(path.resolve()))}"
    else:
        raise ConfigError(f"base: a dict of the run file's sections or a run file's path, "
                          f"not {type(base).__name__}")
    seeds = _integer("seeds", seeds, 1, 100_000)
    lines = [base_line, f"seeds = {seeds}"]

    def table(name: str, axes: Mapping[str, Sequence[Any]], where: str) -> None:
        if not isinstance(axes, Mapping):
            raise ConfigError(f"{where}: a dict of dotted keys and lists of values")
        lines.append(name)
        for key, values in axes.items():
            if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
                raise ConfigError(f"{where}.{key}: a list of values, not {values!r}")
            lines.append(f"{_toml_key(key)} = {_toml_value(list(values), f'{where}.{key}')}")

    if vary:
        table("[vary]", vary, "vary")
    if zip is not None and (isinstance(zip, Mapping) or not isinstance(zip, (list, tuple))):
        raise ConfigError("zip: a list of dicts, each of keys whose lists vary together")
    for k, axes in enumerate(zip or []):
        table("[[zip]]", axes, f"zip[{k}]")
    return "\n".join(lines) + "\n"


def _integer(name: str, value: Any, low: int, high: int) -> int:
    """An integer argument (Python's or numpy's) in low ..= high, else ConfigError."""
    try:
        if isinstance(value, bool):
            raise TypeError
        number = operator.index(value)
    except TypeError:
        raise ConfigError(f"{name}: {value!r} is not an integer; allowed: {low} ..= {high}")
    if not low <= number <= high:
        raise ConfigError(f"{name}: {number} is out of range; allowed: {low} ..= {high}")
    return number


def _run_one(text: str, origin: str, output_dir: str, point: int, replica: int,
             threads: int, checkpoint_every: Optional[int]) -> Dict[str, Any]:
    """One run of a study, in a worker: its outcome (a dict, as in ``study.json``)."""
    outcome: Dict[str, Any] = json.loads(_haff.study_run(
        text, origin, output_dir, point, replica, threads, checkpoint_every))
    return outcome


def _is_dask(executor: Any) -> bool:
    # A dask Client exists only once `distributed` is imported: no import (seconds) here.
    if "distributed" not in sys.modules:
        return False
    from distributed import Client
    return isinstance(executor, Client)


@dataclass
class StudyResult:
    """What :func:`study` gives back; every table is also a file in ``output_dir``.

    Parameters
    ----------
    output_dir : pathlib.Path
        The study's directory (absolute).
    ensemble : pandas.DataFrame
        ``ensemble.csv``: a row per point, sample and quantity, with the columns
        ``point``, the varied keys, ``sample``, ``time``, ``collisions_per_particle``
        (the replicas' means), ``quantity`` (a column of the runs' ``timeseries.csv``),
        ``mean``, ``standard_error`` (the sample standard deviation over the replicas
        over sqrt(replicas); NaN for one replica) and ``replicas``.
    runs : pandas.DataFrame
        A row per run: ``point``, ``replica``, ``seed``, ``dir`` (relative to
        `output_dir`), ``state`` (``complete`` or ``failed``), ``wall_seconds``,
        ``resumed``, ``kept`` (finished by an earlier call), ``error``.
    summary : dict
        ``study.json``: the study, its keys and points, per point the scalars of the
        runs' ``summary.json`` with mean and standard error, every run's outcome.
    dataset : xarray.Dataset or None
        Every quantity of every complete run, dims ``(run, sample)``, with the point, the
        seed and the varied keys as coordinates of ``run``; None without xarray.
    failed : list of dict
        The outcomes of the runs that failed and the invalid points left out (empty when
        everything ran).

    Examples
    --------
    >>> import haff
    >>> gas = {"system": {"particles": 200, "packing_fraction": 0.1, "seed": 1},
    ...        "collision": {"law": "constant", "restitution": 0.9},
    ...        "run": {"collisions_per_particle": 10, "samples": 3}}
    >>> result = haff.study(gas, vary={"collision.restitution": [0.7, 0.9]}, seeds=3,
    ...                     output_dir="result-study", progress=False)
    >>> result.runs[["point", "seed", "dir", "state"]]
       point  seed         dir     state
    0      0     1  runs/000/1  complete
    1      0     2  runs/000/2  complete
    2      0     3  runs/000/3  complete
    3      1     1  runs/001/1  complete
    4      1     2  runs/001/2  complete
    5      1     3  runs/001/3  complete
    >>> result.failed
    []
    >>> result.dataset["temperature"].shape      # (run, sample)
    (6, 3)
    """

    output_dir: Path
    ensemble: Any
    runs: Any
    summary: Dict[str, Any]
    dataset: Any = None
    failed: List[Dict[str, Any]] = field(default_factory=list)


def study(base: Union[Mapping[str, Any], PathLike],
          vary: Optional[Mapping[str, Sequence[Any]]] = None,
          seeds: int = 1, *,
          output_dir: PathLike,
          zip: Optional[Sequence[Mapping[str, Sequence[Any]]]] = None,
          executor: Any = None,
          jobs: int = 1,
          threads: int = 1,
          checkpoint_every: Optional[int] = None,
          force: bool = False,
          keep_going: bool = False,
          progress: Union[None, bool, Callable[[int, int, str], None]] = None) -> StudyResult:
    """Runs a study: many runs of one run file over a grid of parameters and seeds.

    Every point of `vary` (and `zip`) times `seeds` replicas of `base`: the same study,
    the same run files and the same ``ensemble.csv`` (byte for byte) as ``haff study``
    (docs/studies.md), each run a complete ``haff run`` in
    ``output_dir/runs/<point>/<seed>/``. The aggregates — the mean and standard error over
    the replicas at every sample — are computed here from the runs' files.

    Parameters
    ----------
    base : dict, str or path
        The run: the run file's sections as a dict (as for :class:`Simulation`), or a
        run file's path.
    vary : dict of str to list, optional
        Dotted keys of the run file and their lists of values, whose cross product makes
        the points, e.g. ``{"collision.restitution": [0.5, 0.7, 0.9]}``; the last key
        varies fastest. ``system.seed`` cannot be varied.
    seeds : int, default 1
        Replicas per point (1..100000); replica r runs with ``system.seed`` = base seed
        + r.
    output_dir : str or path
        The study's directory: new, empty, or this study's to continue it (finished runs
        are kept, interrupted ones resume from their check-points). Workers of a remote
        executor must see it at the same path.
    zip : list of dict, optional
        Tables of keys whose lists (of equal length) vary together, each one axis.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where the runs go (a ``ProcessPoolExecutor``, a dask ``Client`` of a
        ``LocalCluster`` or of a Slurm/PBS cluster by ``dask-jobqueue``); None: a pool of
        `jobs` threads here (the runs release the GIL).
    jobs : int, default 1
        Runs at a time on the threads of the default executor.
    threads : int, default 1
        Threads per run.
    checkpoint_every : int, optional
        Samples between check-points (default: at the first sample after each minute of
        a run, as ``haff study``).
    force : bool, default False
        Replace another study's directory.
    keep_going : bool, default False
        Leave out invalid points (listed in ``failed``) instead of raising.
    progress : bool, None or callable, default None
        A bar over the runs (tqdm's if installed; None: when interactive), or a callable
        ``(done, total, note)`` called as runs finish.

    Returns
    -------
    StudyResult
        ``ensemble`` (mean and standard error per point, sample and quantity), ``runs``,
        ``summary``, ``dataset`` and ``failed``.

    Raises
    ------
    ConfigError
        A bad study, naming the point and key, before any run starts; a directory
        holding another study (without `force`) or other files.
    ImportError
        pandas is not installed.

    Notes
    -----
    A run that fails does not stop the others: its outcome is in ``failed``. Calling
    ``study`` again with the same arguments keeps the finished runs and resumes the
    others. Ctrl-C cancels the runs not started.

    Examples
    --------
    The temperature after 10 collisions per particle at two restitutions, 3 seeds each:

    >>> import haff
    >>> gas = {"system": {"particles": 200, "packing_fraction": 0.1, "seed": 1},
    ...        "collision": {"law": "constant", "restitution": 0.9},
    ...        "run": {"collisions_per_particle": 10, "samples": 3}}
    >>> result = haff.study(gas, vary={"collision.restitution": [0.7, 0.9]}, seeds=3,
    ...                     output_dir="eps-study", progress=False)
    >>> e = result.ensemble
    >>> end = e[(e["quantity"] == "temperature") & (e["sample"] == 2)]
    >>> end[["collision.restitution", "mean", "standard_error", "replicas"]].round(4)
        collision.restitution    mean  standard_error  replicas
    10                    0.7  0.1748          0.0066         3
    25                    0.9  0.5216          0.0074         3
    """
    try:
        import pandas  # noqa: F401  (the results' tables: checked before any run)
    except ImportError:
        raise ImportError("haff.study returns pandas tables: pip install pandas") from None
    text = study_toml(base, vary, seeds, zip)
    jobs = _integer("jobs", jobs, 1, 4096)
    threads = _integer("threads", threads, 1, 4096)
    if checkpoint_every is not None:
        checkpoint_every = _integer("checkpoint_every", checkpoint_every, 1, 1_000_000)
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise ConfigError(f"executor: a concurrent.futures.Executor or a dask Client, not "
                          f"{type(executor).__name__}")
    if not isinstance(output_dir, (str, os.PathLike)):
        raise ConfigError(f"output_dir: a path, not {type(output_dir).__name__}")
    keys, points, runs, invalid = _haff.study_plan(text, _ORIGIN, bool(keep_going))
    directory = Path(os.fspath(output_dir)).resolve()
    try:
        _haff.study_open(text, _ORIGIN, str(directory), bool(force))
    except ConfigError as error:  # the command's wording, in this function's names
        raise ConfigError(str(error).replace("--out", "output_dir")
                          .replace("--force", "force=True")) from None
    report = _progress(progress, len(runs))
    own = executor is None
    if own:
        executor = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)
    outcomes: Dict[int, Dict[str, Any]] = {}
    try:
        args = [(text, _ORIGIN, str(directory), p, r, threads, checkpoint_every)
                for p, r, _ in runs]
        as_completed: Callable[[List[Any]], Iterable[Any]]
        if _is_dask(executor):
            from distributed import as_completed as dask_as_completed
            as_completed = dask_as_completed
            futures = [executor.submit(_run_one, *a, pure=False) for a in args]
        else:
            as_completed = concurrent.futures.as_completed
            futures = [executor.submit(_run_one, *a) for a in args]
        index = {id(f): k for k, f in enumerate(futures)}
        done = 0
        try:
            for future in as_completed(futures):
                k = index[id(future)]
                try:
                    outcomes[k] = future.result()
                except Exception as error:  # a lost worker, a broken pool: the run stays
                    p, r, s = runs[k]       # resumable; the others go on
                    outcomes[k] = {"point": p, "replica": r, "seed": s,
                                   "dir": f"runs/{p:03d}/{s}", "state": "failed",
                                   "wall_seconds": None, "resumed": False, "kept": False,
                                   "error": f"{type(error).__name__}: {error}"}
                done += 1
                if report is not None:
                    o = outcomes[k]
                    report(done, len(runs), f"{o['point']:03d}/{o['seed']} {o['state']}")
        except BaseException:  # Ctrl-C: the runs not started are cancelled; those in
            for f in futures:  # flight finish (or stay resumable from their check-points)
                f.cancel()
            raise
    finally:
        if own:
            executor.shutdown(wait=True, cancel_futures=True)
    ordered = [outcomes[k] for k in sorted(outcomes)]
    summary = json.loads(_haff.study_aggregate(
        text, _ORIGIN, str(directory), [json.dumps(o) for o in ordered], list(invalid)))
    failed = [o for o in ordered if o["state"] != "complete"]
    failed += [{"point": p, "state": "invalid", "error": e} for p, e in invalid]
    return _result(directory, keys, [json.loads(v) for v in points], ordered, summary, failed)


def _progress(progress: Union[None, bool, Callable[[int, int, str], None]],
              total: int) -> Optional[Callable[[int, int, str], None]]:
    if callable(progress):
        return progress
    if progress is None:
        progress = _interactive()
    if not progress:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    if total == 0:
        return None
    bar = tqdm(total=total, unit="run")

    def report(done: int, total: int, note: str) -> None:
        bar.n = done
        bar.set_postfix_str(note, refresh=False)
        bar.refresh()
        if done >= total:
            bar.close()

    return report


def _result(directory: Path, keys: List[str], points: List[Dict[str, Any]],
            outcomes: List[Dict[str, Any]], summary: Dict[str, Any],
            failed: List[Dict[str, Any]]) -> StudyResult:
    import pandas as pd

    ensemble = pd.read_csv(directory / "ensemble.csv")
    columns = ["point", "replica", "seed", "dir", "state", "wall_seconds", "resumed", "kept",
               "error"]
    runs = pd.DataFrame(outcomes, columns=columns)
    return StudyResult(directory, ensemble, runs, summary,
                       _dataset(directory, keys, points, outcomes), failed)


def _dataset(directory: Path, keys: List[str], points: List[Dict[str, Any]],
             outcomes: List[Dict[str, Any]]) -> Any:
    """Every complete run's ``timeseries.csv`` as one xarray Dataset (run x sample)."""
    try:
        import xarray as xr
    except ImportError:
        return None
    import numpy as np
    import pandas as pd

    complete = [o for o in outcomes if o["state"] == "complete"]
    if not complete:
        return None
    frames = [pd.read_csv(directory / o["dir"] / "timeseries.csv") for o in complete]
    samples = max(len(f) for f in frames)
    columns = list(dict.fromkeys(c for f in frames for c in f.columns))
    data = {}
    for c in columns:
        block = np.full((len(frames), samples), np.nan)
        for i, f in enumerate(frames):
            if c in f:
                block[i, :len(f)] = f[c].to_numpy(dtype=float)
        data[c] = (("run", "sample"), block)
    coords = {"run": np.arange(len(complete)), "sample": np.arange(samples),
              "point": ("run", [o["point"] for o in complete]),
              "seed": ("run", [o["seed"] for o in complete])}
    for key in keys:
        values: Any = [points[o["point"]].get(key) for o in complete]
        if any(isinstance(v, (list, dict)) for v in values):  # a varied list or table:
            column = np.empty(len(values), dtype=object)       # one object per run
            column[:] = [json.dumps(v) for v in values]
            values = column
        coords[key] = ("run", values)
    try:
        return xr.Dataset(data, coords=coords)
    except Exception as error:  # the tables on disk and in `ensemble` are complete
        warnings.warn(f"haff.study: no xarray Dataset: {error}", RuntimeWarning)
        return None
