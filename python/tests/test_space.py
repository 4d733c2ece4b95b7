"""The observers of space ([output]) from Python: sim.modes() and sim.structure() equal the
modes.csv and structure.csv of `haff run` bit for bit; the snapshots (.vtu, read with
meshio) hold the particles of sim at their time; the fields (.vti, read by a small XML
parser) have the mean density N / L^2; bad [output] values and a missing output directory
raise ConfigError naming the key."""

import base64
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import haff
from conftest import read_csv

PARTICLES, PHI = 400, 0.2
SAMPLES = 5

CONFIG = {
    "system": {"dimension": 2, "particles": PARTICLES, "packing_fraction": PHI, "seed": 4},
    "collision": {"law": "constant", "restitution": 0.9},
    "run": {"collisions_per_particle": 6.0, "samples": SAMPLES, "spacing": "linear"},
    "output": {
        "modes": True,
        "mode_shells": 3,
        "structure": True,
        "fields": {"every": 2, "grid": 8},
        "snapshots": {"every": 2, "format": "vtk"},
    },
}
# The box of N unit disks at the packing fraction.
LENGTH = math.sqrt(PARTICLES * math.pi / 4 / PHI)


def csv_columns(path: Path):
    header, rows = read_csv(path.read_text())
    return {name: [row[i] for row in rows] for i, name in enumerate(header)}


@pytest.fixture(scope="module")
def runs(tmp_path_factory, haff_bin):
    """The run from Python (output directory `py`, written there) and from `haff run`."""
    import subprocess

    root = tmp_path_factory.mktemp("space")
    file = root / "gas.toml"
    file.write_text(haff._simulation.config_to_toml(CONFIG))
    done = subprocess.run([str(haff_bin), "run", str(file), "--out", str(root / "cli")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    sim = haff.Simulation(CONFIG, output_dir=root / "py")
    sim.run(progress=False)
    sim.write()
    return sim, root


def test_modes_and_structure_equal_the_command_bit_for_bit(runs):
    sim, root = runs
    modes = sim.modes()
    columns = csv_columns(root / "cli" / "modes.csv")
    assert list(modes) == list(columns) == [
        "time", "collisions_per_particle", "k", "transverse_energy", "longitudinal_energy",
        "density_power"]
    assert len(modes["k"]) == SAMPLES * 2  # shells |n|^2 = 1, 2 (3 is empty in 2D)
    for name, values in modes.items():
        assert values.dtype == np.float64
        np.testing.assert_array_equal(values, [float(x) for x in columns[name]], err_msg=name)
    structure = sim.structure()
    columns = csv_columns(root / "cli" / "structure.csv")
    assert list(structure) == list(columns)
    assert structure["function"].dtype.kind == "U"
    np.testing.assert_array_equal(structure["function"], columns["function"])
    for name in ("time", "collisions_per_particle", "x", "value"):
        np.testing.assert_array_equal(structure[name], [float(x) for x in columns[name]],
                                      err_msg=name)
    assert set(structure["function"]) == {"S", "g"}
    # sim.write() into the output directory writes the command's files.
    for name in ("modes.csv", "structure.csv", "fields.pvd", "snapshots.pvd",
                 "timeseries.csv", "snapshot_000004.vtu", "fields_000002.vti"):
        assert (root / "py" / name).read_bytes() == (root / "cli" / name).read_bytes(), name


def test_snapshots_hold_the_particles(runs):
    import meshio
    sim, root = runs
    snapshots = sim.snapshot_files()
    times = sim.timeseries["time"]
    assert [t for t, _ in snapshots] == [times[0], times[2], times[4]]
    assert [p.name for _, p in snapshots] == [
        "snapshot_000000.vtu", "snapshot_000002.vtu", "snapshot_000004.vtu"]
    assert all(p.parent == sim.output_dir for _, p in snapshots)
    # The last sample is the end of the run: the snapshot holds the particles now.
    time, path = snapshots[-1]
    assert time == sim.time
    mesh = meshio.read(path)
    assert sorted(mesh.point_data) == ["collisions", "mass", "radius", "species", "velocity"]
    np.testing.assert_array_equal(mesh.points[:, :2], sim.positions)
    np.testing.assert_array_equal(mesh.points[:, 2], 0.0)
    np.testing.assert_array_equal(mesh.point_data["velocity"][:, :2], sim.velocities)
    np.testing.assert_array_equal(mesh.point_data["radius"].ravel(), sim.radii)
    np.testing.assert_array_equal(mesh.point_data["mass"].ravel(), sim.masses)
    np.testing.assert_array_equal(mesh.point_data["species"].ravel(), 0)
    assert mesh.point_data["collisions"].sum() == 2 * sim.collisions
    assert len(mesh.cells) == 1 and mesh.cells[0].type == "vertex"
    assert len(mesh.cells[0].data) == PARTICLES


def read_vti(path: Path):
    """The cell data of a VTK ImageData file (ascii or base64 binary, uncompressed) as
    name -> array (components last), with the grid's extent and spacing."""
    root = ET.parse(path).getroot()
    assert root.get("type") == "ImageData" and root.get("compressor") is None
    header = np.uint64 if root.get("header_type") == "UInt64" else np.uint32
    image = root.find("ImageData")
    extent = [int(x) for x in image.get("WholeExtent").split()]
    spacing = [float(x) for x in image.get("Spacing").split()]
    arrays = {}
    for array in image.find("Piece").find("CellData").findall("DataArray"):
        kind = {"Float64": np.float64, "Float32": np.float32}[array.get("type")]
        text = (array.text or "").strip()
        if array.get("format") == "binary":
            raw = base64.b64decode(text)
            size = int(np.frombuffer(raw[:header().itemsize], header)[0])
            values = np.frombuffer(raw[header().itemsize:header().itemsize + size], kind)
        else:
            assert array.get("format") == "ascii", array.get("format")
            values = np.array(text.split(), dtype=kind)
        components = int(array.get("NumberOfComponents", "1"))
        arrays[array.get("Name")] = values.reshape(-1, components).squeeze()
    return arrays, extent, spacing


def test_fields_have_the_mean_density(runs):
    sim, root = runs
    fields = sim.field_files()
    times = sim.timeseries["time"]
    assert [t for t, _ in fields] == [times[0], times[2], times[4]]
    for _, path in fields:
        arrays, extent, spacing = read_vti(path)
        assert extent == [0, 8, 0, 8, 0, 0]
        assert spacing[0] == pytest.approx(LENGTH / 8, rel=1e-6)  # f32 in the file
        assert sorted(arrays) == ["density", "temperature", "velocity", "vorticity"]
        density = arrays["density"]
        assert density.shape == (64,)
        assert density.mean() == pytest.approx(PARTICLES / LENGTH**2, rel=1e-12)
        assert arrays["velocity"].shape == (64, 3)


def test_bad_output_values_name_the_key(tmp_path):
    def config(**output):
        return {**CONFIG, "output": {**CONFIG["output"], **output}}

    cases = [
        ({"fields": {"every": 2, "grid": 0}}, "output.fields.grid"),
        ({"fields": {"every": 0, "grid": 8}}, "output.fields.every"),
        ({"snapshots": {"every": 1, "format": "csv"}}, "output.snapshots.format"),
        ({"mode_shells": 0}, "output.mode_shells"),
        ({"modes": "yes"}, "output.modes"),
    ]
    for output, key in cases:
        with pytest.raises(haff.ConfigError, match=key.replace(".", r"\.")):
            haff.Simulation(config(**output))
    with pytest.raises(haff.ConfigError, match=r"output\.fields\.grid.*3 \.\.= 4096"):
        haff.Simulation(config(fields={"every": 1, "grid": 0}))


def test_files_need_an_output_directory(tmp_path):
    """Fields or snapshots without an output directory: refused before the run, naming the
    key; with one set afterwards the run is the same as the command's."""
    for output, key in [({}, "output.fields"),
                        ({"fields": None}, "output.snapshots")]:
        body = {k: v for k, v in {**CONFIG["output"], **output}.items() if v is not None}
        sim = haff.Simulation({**CONFIG, "output": body})
        assert sim.output_dir is None
        for go in (lambda: sim.run(progress=False), lambda: sim.advance(time=0.1)):
            with pytest.raises(haff.ConfigError, match=key.replace(".", r"\.")
                               + r": writes .* output directory"):
                go()
        assert len(sim.timeseries["time"]) == 0 and len(sim.modes()["k"]) == 0
        with pytest.raises(haff.ConfigError, match="dir"):
            sim.write()
    # Without fields and snapshots no directory is needed.
    body = {k: v for k, v in CONFIG["output"].items() if k in ("modes", "structure")}
    assert haff.Simulation({**CONFIG, "output": body}).run(progress=False).complete
    # Setting the directory later; the directory is claimed as `haff run --out` claims it.
    sim = haff.Simulation(CONFIG)
    sim.output_dir = tmp_path / "later"
    assert sim.output_dir == tmp_path / "later"
    assert (tmp_path / "later" / "haff-run.json").exists()
    sim.advance(collisions_per_particle=3.0)
    assert [p.name for _, p in sim.snapshot_files()] == [
        "snapshot_000000.vtu", "snapshot_000002.vtu"]
    assert all(p.exists() for _, p in sim.snapshot_files() + sim.field_files())
    # Another run's directory is refused (force replaces its outputs); other files too.
    other = {**CONFIG, "system": {**CONFIG["system"], "seed": 5}}
    with pytest.raises(haff.ConfigError, match="output_dir: .*another haff run"):
        haff.Simulation(other, output_dir=tmp_path / "later")
    haff.Simulation(other, output_dir=tmp_path / "later", force=True)
    (tmp_path / "foreign").mkdir()
    (tmp_path / "foreign" / "notes.txt").write_text("mine")
    with pytest.raises(haff.ConfigError, match="output_dir: .*notes.txt"):
        sim.output_dir = tmp_path / "foreign"
    with pytest.raises(haff.ConfigError, match="output_dir"):
        sim.output_dir = None


def test_a_loaded_run_continues_into_its_directory(tmp_path):
    """save/load keep the records of space; the output directory is given again, and the
    loaded run writes what the saved one writes going on (bit for bit)."""
    sim = haff.Simulation(CONFIG, output_dir=tmp_path / "saved")
    sim.advance(collisions_per_particle=3.0)
    sim.save(tmp_path / "state.bin")
    loaded = haff.Simulation.load(tmp_path / "state.bin")
    assert loaded.output_dir is None
    assert [p for _, p in loaded.snapshot_files()] == [
        Path("snapshot_000000.vtu"), Path("snapshot_000002.vtu")]
    with pytest.raises(haff.ConfigError, match=r"output\.fields"):
        loaded.run(progress=False)
    loaded.output_dir = tmp_path / "loaded"
    loaded.run(progress=False)
    loaded.write()
    sim.run(progress=False)
    sim.write()
    for name in ("modes.csv", "structure.csv", "snapshot_000004.vtu", "fields_000004.vti",
                 "fields.pvd", "snapshots.pvd"):
        saved, continued = tmp_path / "saved" / name, tmp_path / "loaded" / name
        assert saved.read_bytes() == continued.read_bytes(), name
