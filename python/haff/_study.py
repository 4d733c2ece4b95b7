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
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

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
    """The study file (TOML text) of these arguments; a base path is made absolute."""
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
    return json.loads(_haff.study_run(text, origin, output_dir, point, replica, threads,
                                      checkpoint_every))


def _is_dask(executor: Any) -> bool:
    try:
        from distributed import Client
    except ImportError:
        return False
    return isinstance(executor, Client)


@dataclass
class StudyResult:
    """What a study gives back (every table is also a file in ``output_dir``).

    ensemble: ``ensemble.csv`` as a pandas DataFrame (a row per point, sample and quantity:
        mean and standard error over the replicas).
    runs: a DataFrame of the runs (point, replica, seed, dir, state, wall_seconds, resumed,
        kept, error).
    summary: ``study.json`` (the study, the points' summary scalars with mean and standard
        error, every run's outcome).
    dataset: an xarray Dataset of every quantity of every complete run, dims
        ``(run, sample)`` with the point, seed and varied keys as coordinates of ``run``
        (None when xarray is not installed).
    failed: the outcomes of the runs that failed and the points left out (empty when
        everything ran).
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
    """Runs a study: every point of ``vary`` (and ``zip``) times ``seeds`` replicas of
    ``base``, the same study and directory layout as ``haff study``.

    base: the run file's sections as a dict, or a run file's path.
    vary: dotted keys of the run file and their lists of values (the cross product), e.g.
        ``{"collision.restitution": [0.5, 0.7, 0.9]}``.
    seeds: replicas per point; replica r runs with ``system.seed`` = base seed + r.
    output_dir: the study's directory (new, empty, or this study's to continue it: finished
        runs are kept, interrupted ones resume from their check-points). Workers of a remote
        executor must see it at the same path.
    zip: tables of keys whose lists vary together (each one axis).
    executor: a ``concurrent.futures.Executor`` or a ``dask.distributed.Client``; None: a
        pool of ``jobs`` threads here.
    threads: threads per run. checkpoint_every: samples between check-points (default: at
        the first sample after each minute of a run, as ``haff study``).
    force: replace another study's directory. keep_going: leave out invalid points (listed
        in ``failed``) instead of raising ``ConfigError``.
    progress: a bar over the runs (tqdm's if installed; None: when interactive), or a
        callable ``(done, total, note)``.

    Raises ``ConfigError`` for a bad study (naming the point and key) before any run starts.
    A run that fails does not stop the others; its outcome is in ``failed``.
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
        if _is_dask(executor):
            from distributed import as_completed
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


def _progress(progress, total):
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
             outcomes: List[Dict[str, Any]]):
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
        values = [points[o["point"]].get(key) for o in complete]
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
