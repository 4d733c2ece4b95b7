"""H5MD and LAMMPS data files from Python (issue 38). H5MD: h5py (the reference HDF5 reader
of Python) opens what haff writes and finds the H5MD 1.1 layout (www.nongnu.org/h5md/h5md.html:
groups, attributes, shapes, dtypes) and the values written, bit for bit; haff reads a file
h5py writes as another H5MD writer would. Skipped only where haff was built without the
feature `h5md` (scripts/test builds it with it). LAMMPS data files: the round trip, masses
within one ulp (the file holds densities; oracle: the masses written)."""

import numpy as np
import pytest

import haff

from test_particles import configuration


def h5md_or_skip(tmp_path, c):
    path = tmp_path / "gas.h5"
    try:
        haff.write_configuration(path, "h5md", c)
    except haff.ConfigError as e:
        if "built without H5MD" in str(e):
            pytest.skip("haff built without the feature h5md")
        raise
    return path


@pytest.mark.parametrize("dimension", [2, 3])
def test_h5py_reads_the_h5md_layout(tmp_path, dimension):
    h5py = pytest.importorskip("h5py")
    c = {**configuration(dimension), "time": 2.5}
    path = h5md_or_skip(tmp_path, c)
    n = len(c["positions"])
    with h5py.File(path, "r") as f:
        assert list(f["h5md"].attrs["version"]) == [1, 1]
        assert f["h5md/author"].attrs["name"]
        assert f["h5md/creator"].attrs["name"] == "haff"
        assert f["h5md/creator"].attrs["version"]
        box = f["particles/all/box"]
        assert box.attrs["dimension"] == dimension
        assert list(box.attrs["boundary"]) == ["periodic"] * dimension
        np.testing.assert_array_equal(box["edges"][()], c["box"])
        for name, key, width in (("position", "positions", dimension),
                                 ("velocity", "velocities", dimension),
                                 ("angular_velocity", "spins", 3)):
            element = f[f"particles/all/{name}"]
            value = element["value"]
            assert value.shape == (1, n, width) and value.dtype == np.float64, name
            np.testing.assert_array_equal(value[0], c[key], err_msg=name)
            assert element["step"].dtype.kind == "i" and list(element["step"][()]) == [0]
            assert list(element["time"][()]) == [2.5]
        for name, key, kind in (("species", "species", "i"), ("mass", "masses", "f"),
                                ("diameter", "diameters", "f")):
            data = f[f"particles/all/{name}"]
            assert data.shape == (n,) and data.dtype.kind == kind, name
            np.testing.assert_array_equal(data[()], c[key], err_msg=name)
    back = haff.read_configuration(path, "h5md", dimension=dimension)
    assert set(back) == set(c)
    for key, value in c.items():
        np.testing.assert_array_equal(back[key], np.asarray(value), err_msg=key)


def test_haff_reads_an_h5md_file_h5py_wrote(tmp_path):
    """Another writer's choices: a scalar `step` with an `offset`, no `time`, fixed-length
    strings, species as int64, positions outside the box (wrapped), two frames."""
    h5py = pytest.importorskip("h5py")
    h5md_or_skip(tmp_path, configuration(3))
    rng = np.random.default_rng(3)
    n, side = 8, 10.0
    frames = np.stack([(np.indices((2, 2, 2)).reshape(3, -1).T * 5.0 + 1.0 + k)
                       for k in range(2)])
    frames[1, 0, 0] -= side  # outside: wrapped into the box
    velocities = rng.normal(size=(2, n, 3))
    path = tmp_path / "other.h5"
    with h5py.File(path, "w") as f:
        f.create_group("h5md").attrs["version"] = np.array([1, 0], dtype=np.int32)
        box = f.create_group("particles/all/box")
        box.attrs["dimension"] = 3
        box.attrs["boundary"] = np.array([b"periodic"] * 3, dtype="S8")
        box["edges"] = np.full(3, side)
        for name, data in (("position", frames), ("velocity", velocities)):
            g = f.create_group(f"particles/all/{name}")
            g["value"] = data
            g["step"] = np.int64(100)
            g["step"].attrs["offset"] = 1000
        f["particles/all/species"] = np.arange(n, dtype=np.int64) % 2
    c = haff.read_configuration(path, "h5md", frame=-1)
    expected = frames[1].copy()
    expected[0, 0] += side
    np.testing.assert_array_equal(c["positions"], expected)
    np.testing.assert_array_equal(c["velocities"], velocities[1])
    np.testing.assert_array_equal(c["species"], np.arange(n) % 2)
    first = haff.read_configuration(path, "h5md", frame=0)
    np.testing.assert_array_equal(first["positions"], frames[0])
    assert "time" not in c


@pytest.mark.parametrize("dimension", [2, 3])
def test_lammps_data_round_trip(tmp_path, dimension):
    c = configuration(dimension)
    path = tmp_path / "gas.data"
    haff.write_configuration(path, "lammps-data", c)
    back = haff.read_configuration(path, "lammps-data", dimension=dimension)
    assert set(back) == set(c)
    for key, value in c.items():
        if key == "masses":
            np.testing.assert_array_max_ulp(back[key], value, maxulp=1)
        else:
            np.testing.assert_array_equal(back[key], np.asarray(value), err_msg=key)


def test_h5py_reads_the_snapshot_trajectory(tmp_path):
    """`[output] snapshots = { format = "h5md" }`: h5py finds a frame per snapshot (value
    (frames, N, D), step = the sample's number, time = the sample's) and the observables
    temperature and energy_lost of the run's timeseries at those samples (oracle: the
    timeseries; T to 1e-14 relative, the same sum in another order)."""
    h5py = pytest.importorskip("h5py")
    config = {"system": {"dimension": 2, "particles": 60, "packing_fraction": 0.2},
              "collision": {"law": "constant", "restitution": 0.8},
              "run": {"collisions_per_particle": 4, "samples": 5, "spacing": "linear"},
              "output": {"snapshots": {"every": 2, "format": "h5md"}}}
    try:
        sim = haff.Simulation(config, output_dir=tmp_path / "run").run()
    except haff.ConfigError as e:
        if "without H5MD" in str(e):
            pytest.skip("haff built without the feature h5md")
        raise
    ts = sim.timeseries
    with h5py.File(tmp_path / "run" / "snapshots.h5md", "r") as f:
        position = f["particles/all/position"]
        assert position["value"].shape == (3, 60, 2)
        assert list(position["step"][()]) == [0, 2, 4]
        np.testing.assert_array_equal(position["time"][()], ts["time"][[0, 2, 4]])
        temperature = f["observables/temperature/value"][()]
        np.testing.assert_allclose(temperature, ts["temperature"][[0, 2, 4]], rtol=1e-14)
        np.testing.assert_array_equal(f["observables/energy_lost/value"][()],
                                      ts["energy_lost"][[0, 2, 4]])
