"""Particle files (issue 38): haff.write_configuration / haff.read_configuration round trips
in every format, bit for bit; the community's readers (OVITO's Python module, ASE) open what
haff writes and find N, the box and the velocities; bad files and configurations raise
ConfigError naming the record and field."""

import numpy as np
import pytest

import haff

FORMATS = ("csv", "lammps-dump", "xyz")


def configuration(dimension=3, n_side=6, seed=1):
    """A jittered lattice of spheres (no overlaps) with every optional column."""
    rng = np.random.default_rng(seed)
    spacing = 1.7
    grid = (np.indices((n_side,) * dimension).reshape(dimension, -1).T + 0.5) * spacing
    positions = grid + rng.uniform(-0.3, 0.3, grid.shape)
    n = len(positions)
    spins = rng.normal(size=(n, 3))
    if dimension == 2:
        spins[:, :2] = 0.0
    return {"box": [spacing * n_side] * dimension, "positions": positions,
            "velocities": rng.normal(size=(n, dimension)) * 10.0 ** rng.uniform(-3, 2, (n, 1)),
            "diameters": rng.uniform(0.8, 1.0, n), "masses": rng.uniform(0.5, 2.0, n),
            "species": np.arange(n) % 3, "spins": spins}


@pytest.mark.parametrize("dimension", [2, 3])
@pytest.mark.parametrize("format", FORMATS)
def test_every_format_reads_back_bit_for_bit(tmp_path, format, dimension):
    original = configuration(dimension)
    path = tmp_path / f"gas.{format}"
    haff.write_configuration(path, format, original)
    back = haff.read_configuration(path, format, dimension=dimension)
    assert set(back) == set(original)
    for key, value in original.items():
        np.testing.assert_array_equal(back[key], np.asarray(value), err_msg=key)


def test_ovito_opens_the_dump_and_the_xyz_file(tmp_path):
    """OVITO's own readers (its text parser rounds within 2 ulp: 1e-15 relative)."""
    import_file = pytest.importorskip("ovito.io").import_file
    original = configuration(3)
    for format, ovito_format in (("lammps-dump", "lammps/dump"), ("xyz", None)):
        path = tmp_path / f"gas.{format}"
        haff.write_configuration(path, format, original)
        pipeline = (import_file(str(path), input_format=ovito_format) if ovito_format
                    else import_file(str(path)))
        data = pipeline.compute()
        assert data.particles.count == len(original["positions"])
        np.testing.assert_allclose(np.diag(np.asarray(data.cell[:3, :3])), original["box"],
                                   rtol=1e-15)
        for name, key in (("Position", "positions"), ("Velocity", "velocities")):
            np.testing.assert_allclose(np.asarray(data.particles[name][...]), original[key],
                                       rtol=1e-15, atol=1e-15, err_msg=f"{format} {name}")
        # OVITO keeps radii in single precision, parsed to within one float32 ulp (2^-23
        # of the binade's lower end: 1.2e-7 relative).
        np.testing.assert_allclose(np.asarray(data.particles["Radius"][...]),
                                   original["diameters"] / 2, rtol=2.0 ** -23)
        np.testing.assert_array_equal(np.asarray(data.particles["Particle Type"][...]),
                                      original["species"] + 1)


def test_ase_reads_the_xyz_file(tmp_path):
    ase_io = pytest.importorskip("ase.io")
    original = configuration(3)
    path = tmp_path / "gas.xyz"
    haff.write_configuration(path, "xyz", original)
    atoms = ase_io.read(str(path), format="extxyz")
    assert len(atoms) == len(original["positions"])
    np.testing.assert_allclose(atoms.cell.lengths(), original["box"], rtol=1e-15)
    np.testing.assert_allclose(atoms.positions, original["positions"], rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(atoms.arrays["velo"], original["velocities"], rtol=1e-15,
                               atol=1e-15)
    np.testing.assert_array_equal(atoms.arrays["type"], original["species"] + 1)


def test_bad_configurations_raise_naming_the_record(tmp_path):
    c = configuration(3)
    c["positions"][7] = c["positions"][2]
    with pytest.raises(haff.ConfigError, match="records 2 and 7.*overlap"):
        haff.write_configuration(tmp_path / "a.csv", "csv", c)
    c = configuration(3)
    c["velocities"][4, 1] = np.inf
    with pytest.raises(haff.ConfigError, match="record 4.*velocity"):
        haff.write_configuration(tmp_path / "a.csv", "csv", c)
    with pytest.raises(haff.ConfigError, match="format.*csv, lammps-dump, xyz"):
        haff.write_configuration(tmp_path / "a.pdb", "pdb", configuration(3))
    with pytest.raises(haff.ConfigError, match="unknown keys"):
        haff.write_configuration(tmp_path / "a.csv", "csv", {**configuration(3), "charge": 1})
    (tmp_path / "b.csv").write_text("# box = 4 4 4\nx,y,z\n1,1,1\n1.5,1,1\n")
    with pytest.raises(haff.ConfigError, match="b.csv: records 0 and 1: the spheres overlap"):
        haff.read_configuration(tmp_path / "b.csv", "csv")
    unchecked = haff.read_configuration(tmp_path / "b.csv", "csv", check=False)
    assert unchecked["positions"].shape == (2, 3)


RUN = {"collision": {"law": "constant", "restitution": 0.8},
       "run": {"collisions_per_particle": 2, "samples": 3}}


def test_a_simulation_from_arrays_is_the_run_from_the_file(tmp_path):
    """Oracle: the exact round trip. Arrays given to haff.Simulation(initial=...) start
    the same run as the file written from them (system.initial.file) and as the CLI's
    run of that file: timeseries equal bit for bit."""
    c = configuration(dimension=2, n_side=10)
    c["masses"] = np.full(len(c["positions"]), 1.0)  # labels of one kind per (d, m)
    c["diameters"] = np.full(len(c["positions"]), 0.9)
    del c["spins"]
    path = tmp_path / "gas.xyz"
    haff.write_configuration(path, "xyz", c)
    from_arrays = haff.Simulation({"system": {"dimension": 2}, **RUN}, initial=c).run()
    from_file = haff.Simulation(
        {"system": {"dimension": 2, "initial": {"file": str(path)}}, **RUN}).run()
    for key, value in from_file.timeseries.items():
        np.testing.assert_array_equal(from_arrays.timeseries[key], value, err_msg=key)
    assert from_arrays.config["system"]["particles"] == len(c["positions"])


def test_a_simulation_from_arrays_draws_missing_velocities():
    """Oracle: exact sums. Without velocities they are drawn at system.temperature:
    T = sum m v^2 / (N D) = 1.5 and no momentum, to round-off."""
    c = configuration(dimension=2, n_side=10)
    for key in ("velocities", "spins", "species", "masses"):
        del c[key]
    c["diameters"] = np.full(len(c["positions"]), 0.9)
    sim = haff.Simulation({"system": {"dimension": 2, "temperature": 1.5}, **RUN}, initial=c)
    assert sim.run().timeseries["temperature"][0] == pytest.approx(1.5, rel=1e-12)


def test_bad_initial_arrays_raise_naming_the_record():
    c = configuration(dimension=2, n_side=4)
    c["positions"][1] = c["positions"][0]
    with pytest.raises(haff.ConfigError, match="records 0 and 1"):
        haff.Simulation({"system": {"dimension": 2}, **RUN}, initial=c)
    with pytest.raises(haff.ConfigError, match="system.particles"):
        haff.Simulation({"system": {"dimension": 2, "particles": 16}, **RUN},
                        initial=configuration(dimension=2, n_side=4))
    with pytest.raises(haff.ConfigError, match="positions"):
        haff.Simulation({"system": {"dimension": 2}, **RUN}, initial={"box": [3.0, 3.0]})
