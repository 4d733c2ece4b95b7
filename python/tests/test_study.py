"""haff.study: the same study as ``haff study`` on threads, processes and a dask
LocalCluster (issue 37). Oracles: the command's own study (byte-identical run files and
ensemble), the mean and standard error recomputed here from the runs' timeseries.csv, and
the executors against one another (byte-identical run files)."""

import concurrent.futures
import multiprocessing
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import haff

BASE = {"system": {"particles": 200, "packing_fraction": 0.05, "seed": 3},
        "collision": {"law": "constant", "restitution": 0.9},
        "run": {"collisions_per_particle": 10, "samples": 6}}
VARY = {"collision.restitution": [0.6, 0.9]}
SEEDS = 3


def run_files(out: Path):
    """Every file of the runs but summary.json (wall-clock times), by relative path."""
    return {str(p.relative_to(out)): p.read_bytes()
            for p in sorted((out / "runs").rglob("*"))
            if p.is_file() and p.name != "summary.json"}


@pytest.fixture(scope="module")
def threads_study(tmp_path_factory):
    out = tmp_path_factory.mktemp("threads") / "study"
    return haff.study(BASE, VARY, seeds=SEEDS, output_dir=out, jobs=2, progress=False)


def test_the_same_study_as_the_command(threads_study, cli, tmp_path):
    run_file = tmp_path / "gas.toml"
    run_file.write_text(haff._simulation.config_to_toml(BASE))
    study_file = tmp_path / "study.toml"
    study_file.write_text(f'base = "gas.toml"\nseeds = {SEEDS}\n[vary]\n'
                          f'"collision.restitution" = [0.6, 0.9]\n')
    cli("study", str(study_file), "--out", str(tmp_path / "command"), "--jobs", "2")
    command = tmp_path / "command"
    assert run_files(command) == run_files(threads_study.output_dir)
    assert (command / "ensemble.csv").read_bytes() == \
        (threads_study.output_dir / "ensemble.csv").read_bytes()


def test_the_ensemble_is_the_mean_and_standard_error_of_the_runs(threads_study):
    """Recomputed here with pandas (sample standard deviation / sqrt(n)); 1e-12 relative:
    the same sums in another order."""
    ensemble = threads_study.ensemble
    assert list(ensemble.columns) == ["point", "collision.restitution", "sample", "time",
                                      "collisions_per_particle", "quantity", "mean",
                                      "standard_error", "replicas"]
    assert (threads_study.runs["state"] == "complete").all()
    for point in (0, 1):
        runs = threads_study.runs[threads_study.runs["point"] == point]
        frames = [pd.read_csv(threads_study.output_dir / d / "timeseries.csv")
                  for d in runs["dir"]]
        rows = ensemble[ensemble["point"] == point]
        for quantity in ("temperature", "a2", "energy_lost"):
            mine = rows[rows["quantity"] == quantity].sort_values("sample")
            values = np.array([f[quantity].to_numpy() for f in frames])
            mean = values.mean(axis=0)
            error = values.std(axis=0, ddof=1) / np.sqrt(SEEDS)
            np.testing.assert_allclose(mine["mean"], mean, rtol=1e-12, atol=1e-300)
            np.testing.assert_allclose(mine["standard_error"], error, rtol=1e-12,
                                       atol=1e-15 * np.abs(mean).max())
            assert (mine["replicas"] == SEEDS).all()
    point = threads_study.summary["points"][1]
    assert point["values"] == {"collision.restitution": 0.9}
    assert point["replicas"] == SEEDS


def test_the_dataset_holds_every_run(threads_study):
    xr = pytest.importorskip("xarray")
    data = threads_study.dataset
    assert isinstance(data, xr.Dataset)
    assert data.sizes == {"run": 2 * SEEDS, "sample": 6}
    assert list(data["seed"].values) == [3, 4, 5, 3, 4, 5]
    first = pd.read_csv(threads_study.output_dir / "runs/001/4/timeseries.csv")
    np.testing.assert_array_equal(data["temperature"].values[4], first["temperature"])
    assert float(data["collision.restitution"][4]) == 0.9


def test_a_process_pool_gives_the_same_bytes(threads_study, tmp_path):
    # Forked processes after threads (and rayon pools) have run in this process.
    fork = multiprocessing.get_context("fork")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=fork) as pool:
        result = haff.study(BASE, VARY, seeds=SEEDS, output_dir=tmp_path / "pool",
                            executor=pool, progress=False)
    assert run_files(result.output_dir) == run_files(threads_study.output_dir)
    assert (result.output_dir / "ensemble.csv").read_bytes() == \
        (threads_study.output_dir / "ensemble.csv").read_bytes()


def test_a_dask_local_cluster_gives_the_same_bytes(threads_study, tmp_path):
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    try:
        with distributed.Client(cluster) as client:
            result = haff.study(BASE, VARY, seeds=SEEDS, output_dir=tmp_path / "dask",
                                executor=client, progress=False)
    finally:
        cluster.close()
    assert (result.runs["state"] == "complete").all()
    assert run_files(result.output_dir) == run_files(threads_study.output_dir)
    assert (result.output_dir / "ensemble.csv").read_bytes() == \
        (threads_study.output_dir / "ensemble.csv").read_bytes()


def test_a_study_continued_keeps_its_finished_runs(threads_study, tmp_path):
    out = tmp_path / "again"
    first = haff.study(BASE, VARY, seeds=SEEDS, output_dir=out, progress=False)
    # A run lost half-way: its manifest says running (its process was killed), its
    # files are gone; the rest is kept.
    lost = out / "runs/001/5"
    for p in lost.iterdir():
        if p.name != "haff-run.json":
            p.unlink()
    manifest = (lost / "haff-run.json").read_text()
    (lost / "haff-run.json").write_text(manifest.replace('"complete"', '"running"'))
    calls = []
    second = haff.study(BASE, VARY, seeds=SEEDS, output_dir=out,
                        progress=lambda done, total, note: calls.append((done, total)))
    assert list(second.runs["kept"]) == [True] * 5 + [False]
    assert calls[-1] == (6, 6)
    assert run_files(out) == run_files(threads_study.output_dir)
    assert (out / "ensemble.csv").read_bytes() == (first.output_dir / "ensemble.csv").read_bytes()


def test_bad_studies_raise_naming_the_point_and_key(tmp_path):
    with pytest.raises(haff.ConfigError, match=r"point 1.*collision\.restitution"):
        haff.study(BASE, {"collision.restitution": [0.5, 1.5]}, output_dir=tmp_path / "a")
    assert not (tmp_path / "a").exists()
    with pytest.raises(haff.ConfigError, match="seeds"):
        haff.study(BASE, VARY, seeds=0, output_dir=tmp_path / "b")
    with pytest.raises(haff.ConfigError, match="jobs"):
        haff.study(BASE, VARY, jobs=0, output_dir=tmp_path / "b")
    with pytest.raises(haff.ConfigError, match="vary.collision.restitution"):
        haff.study(BASE, {"collision.restitution": 0.5}, output_dir=tmp_path / "b")
    with pytest.raises(haff.ConfigError, match="base"):
        haff.study(tmp_path / "missing.toml", VARY, output_dir=tmp_path / "b")
    with pytest.raises(haff.ConfigError, match="system.no_such_key"):
        haff.study(BASE, {"system.no_such_key": [1]}, output_dir=tmp_path / "b")
    for kwargs, name in (({"threads": 10**6}, "threads"), ({"jobs": 1.5}, "jobs"),
                         ({"checkpoint_every": 0}, "checkpoint_every"),
                         ({"seeds": True}, "seeds"), ({"executor": object()}, "executor"),
                         ({"zip": {"a": [1]}}, "zip"), ({"output_dir": 3}, "output_dir")):
        arguments = {"output_dir": tmp_path / "b", **kwargs}
        with pytest.raises(haff.ConfigError, match=name):
            haff.study(BASE, VARY, **arguments)
    assert not (tmp_path / "b").exists()
    # numpy integers are integers
    done = haff.study(BASE, {"collision.restitution": [0.5]}, seeds=np.int64(1),
                      jobs=np.int32(1), output_dir=tmp_path / "c", progress=False)
    assert len(done.runs) == 1
    # another study's directory: named in this function's words
    with pytest.raises(haff.ConfigError, match="output_dir.*force=True"):
        haff.study(BASE, {"collision.restitution": [0.6]}, output_dir=tmp_path / "c")


def test_a_failing_point_does_not_stop_the_others(tmp_path):
    result = haff.study(BASE, {"collision.restitution": [0.5, 1.5, 0.8]}, seeds=2,
                        output_dir=tmp_path / "keep", keep_going=True, progress=False)
    assert [f["point"] for f in result.failed] == [1]
    assert "collision.restitution" in result.failed[0]["error"]
    assert sorted(set(result.ensemble["point"])) == [0, 2]
    assert (result.runs["state"] == "complete").all() and len(result.runs) == 4
    assert (result.output_dir / "figures" / "temperature.png").exists()


def test_the_sonine_hierarchy_against_the_closed_forms():
    """haff.theory.sonine (collisional moments by quadrature) at order 2 against van Noije &
    Ernst's closed form (haff.theory.a2), 1e-10; elastic: the Maxwellian."""
    for dimension in (2, 3):
        for eps in (0.3, 0.5, 0.7, 0.9):
            (first,) = haff.theory.sonine(dimension, eps, order=2)
            assert first == pytest.approx(haff.theory.a2(dimension, eps), rel=1e-10, abs=1e-14)
        assert haff.theory.sonine(dimension, 1.0) == pytest.approx([0.0, 0.0], abs=1e-14)
    assert haff.theory.cooling_per_collision(0.8) == pytest.approx(0.36 / 3, rel=1e-15)
    for bad, name in (((1.5,), "restitution"), ((0.5, 20.0), "a2")):
        with pytest.raises(haff.ConfigError, match=name):
            haff.theory.cooling_per_collision(*bad)
    with pytest.raises(haff.ConfigError, match="order"):
        haff.theory.sonine(3, 0.5, order=-1)
    with pytest.raises(haff.ConfigError, match="order"):
        haff.theory.sonine(3, 0.5, order=1)
    with pytest.raises(haff.ConfigError, match="dimension"):
        haff.theory.sonine(1, 0.5)


class _LosingExecutor(concurrent.futures.ThreadPoolExecutor):
    """Threads, except that the run of point 1, replica 2 is lost (its future raises, as a
    dask future does when its worker dies)."""

    def submit(self, fn, *args, **kwargs):
        if args[3:5] == (1, 2):
            future = concurrent.futures.Future()
            future.set_exception(RuntimeError("worker lost"))
            return future
        return super().submit(fn, *args, **kwargs)


def test_a_lost_worker_fails_its_run_only_and_the_next_call_completes_it(threads_study,
                                                                          tmp_path):
    out = tmp_path / "lost"
    with _LosingExecutor(2) as executor:
        first = haff.study(BASE, VARY, seeds=SEEDS, output_dir=out, executor=executor,
                           progress=False)
    assert [(f["point"], f["seed"]) for f in first.failed] == [(1, 5)]
    assert "worker lost" in first.failed[0]["error"]
    assert (first.ensemble[first.ensemble["point"] == 1]["replicas"] == SEEDS - 1).all()
    second = haff.study(BASE, VARY, seeds=SEEDS, output_dir=out, progress=False)
    assert second.failed == []
    assert list(second.runs["kept"]) == [True] * 5 + [False]
    assert run_files(out) == run_files(threads_study.output_dir)


def test_a_varied_list_is_a_coordinate_of_the_dataset(tmp_path):
    pytest.importorskip("xarray")
    result = haff.study(BASE, {"run.histogram_at": [[0.0, 10.0], [0.0, 5.0]]},
                        output_dir=tmp_path / "lists", progress=False)
    assert list(result.dataset["run.histogram_at"].values) == ["[0.0, 10.0]", "[0.0, 5.0]"]
