"""haff.Simulation: the same run as `haff run`, bit for bit; advance, save/load, write;
bad configs raise ConfigError naming the key; the GIL is released; Ctrl-C interrupts."""

import _thread
import json
import threading
from pathlib import Path

import numpy as np
import pytest

import haff
from conftest import read_csv
from gil import longest_pause_while

CONFIGS = {
    "event-driven": {
        "system": {"dimension": 3, "particles": 500, "packing_fraction": 0.1, "seed": 7},
        "collision": {"law": "constant", "restitution": 0.8},
        "run": {"collisions_per_particle": 40.0, "samples": 9, "histogram_at": [0.0, 40.0]},
    },
    "viscoelastic-2d-by-time": {
        "system": {"dimension": 2, "particles": 400, "packing_fraction": 0.2, "seed": 3,
                   "temperature": 2.0},
        "collision": {"law": "viscoelastic", "form": "fast", "beta": 0.3},
        "run": {"end_time": 3.0, "samples": 7, "spacing": "linear"},
    },
    "dsmc-spatial": {
        "system": {"particles": 2000, "packing_fraction": 0.05, "seed": 11},
        "collision": {"law": "constant", "restitution": 0.9},
        "run": {"engine": "dsmc", "dsmc_scheme": "spatial", "end_time": 4.0, "samples": 5},
    },
    "dsmc-blocks": {
        "system": {"particles": 3000, "packing_fraction": 0.05, "seed": 5},
        "collision": {"law": "constant", "restitution": 0.7},
        "run": {"engine": "dsmc", "collisions_per_particle": 30.0, "samples": 6},
    },
    "rough-dsmc-2d": {
        "system": {"dimension": 2, "particles": 2000, "packing_fraction": 0.05, "seed": 9,
                   "inertia": 0.5, "rotational_temperature": 0.0},
        "collision": {"law": "constant", "restitution": 0.8,
                      "tangential_restitution": 0.4, "friction": 0.2},
        "run": {"engine": "dsmc", "collisions_per_particle": 10.0, "samples": 6},
    },
    "rough-dsmc-spatial": {
        "system": {"particles": 2000, "packing_fraction": 0.05, "seed": 13, "inertia": 0.35},
        "collision": {"law": "constant", "restitution": 0.85,
                      "tangential_restitution": 0.2, "friction": 0.3},
        "run": {"engine": "dsmc", "dsmc_scheme": "spatial", "collisions_per_particle": 8.0,
                "samples": 5},
    },
    "rough-event-driven": {
        "system": {"particles": 500, "packing_fraction": 0.1, "seed": 7, "inertia": 0.4},
        "collision": {"law": "constant", "restitution": 0.8, "tangential_restitution": 0.0},
        "run": {"collisions_per_particle": 10.0, "samples": 5},
    },
    "rough-soft-sphere": {
        "system": {"particles": 300, "packing_fraction": 0.05, "seed": 2, "inertia": 0.4},
        "collision": {"law": "viscoelastic", "young": 1e5, "poisson": 0.3,
                      "dissipative_constant": 0.01, "friction": 0.5},
        "run": {"engine": "soft-sphere", "end_time": 3.0, "samples": 4},
    },
    "soft-sphere": {
        "system": {"particles": 300, "packing_fraction": 0.05, "seed": 2},
        "collision": {"law": "viscoelastic", "young": 1e5, "poisson": 0.3,
                      "dissipative_constant": 0.01},
        "run": {"engine": "soft-sphere", "end_time": 3.0, "samples": 4},
    },
}


def toml_of(config):
    return haff._simulation.config_to_toml(config)


def csv_columns(path: Path):
    header, rows = read_csv(path.read_text())
    return {name: [row[i] for row in rows] for i, name in enumerate(header)}


def assert_equals_csv(timeseries, path: Path):
    """Every column equal to the CSV's, bit for bit (the CSV prints f64 exactly)."""
    columns = csv_columns(path)
    assert list(timeseries) == list(columns)
    for name, values in timeseries.items():
        kind = int if name == "events" else float
        np.testing.assert_array_equal(values, np.array([kind(x) for x in columns[name]]),
                                      err_msg=name)


@pytest.mark.parametrize("name", list(CONFIGS))
def test_a_run_equals_the_command_bit_for_bit(tmp_path, cli, name):
    config = CONFIGS[name]
    file = tmp_path / "gas.toml"
    file.write_text(toml_of(config))
    cli("run", str(file), "--out", str(tmp_path / "cli"))
    sim = haff.Simulation(config).run(progress=False)
    assert sim.complete
    assert_equals_csv(sim.timeseries, tmp_path / "cli" / "timeseries.csv")
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert sim.collisions == summary["collisions"] and sim.events == summary["events"]
    assert sim.config == summary["parameters"]
    # Soft-sphere runs report their contacts; the others have none.
    assert sim.contact_statistics() == summary.get("contacts")
    assert (sim.contact_statistics() is None) == ("soft-sphere" not in name)
    # The same run from the file and from TOML text.
    for source in (file, str(file), file.read_text()):
        other = haff.Simulation(source).run(progress=False)
        np.testing.assert_array_equal(other.timeseries["temperature"],
                                      sim.timeseries["temperature"])


def test_state_arrays_and_observables():
    sim = haff.Simulation(CONFIGS["event-driven"])
    assert sim.positions.shape == (500, 3) and sim.velocities.dtype == np.float64
    sim.run(progress=False)
    v, m = sim.velocities, sim.masses
    # T = <m c^2> / D about the mean velocity (zero for a gas started at rest overall).
    c = v - v.mean(axis=0)
    assert sim.temperature == pytest.approx((m[:, None] * c * c).sum() / (3 * 500), rel=1e-12)
    assert sim.timeseries["temperature"][-1] == sim.temperature
    assert sim.time == sim.timeseries["time"][-1]
    assert sim.collisions_per_particle == pytest.approx(40.0, abs=2 / 500)
    positions = sim.positions
    positions[0, 0] = -1.0  # a copy: the run is untouched
    assert sim.positions[0, 0] >= 0.0
    # Haff's law decreases the temperature; a2 small in 3D at eps = 0.8.
    t = sim.timeseries["temperature"]
    assert np.all(np.diff(t) < 0)
    assert abs(sim.timeseries["a2"][-1]) < 0.1
    hist = sim.velocity_histograms
    assert [h["target"] for h in hist] == [0.0, 40.0]
    assert hist[1]["c"].shape == hist[1]["density"].shape == hist[1]["maxwellian"].shape


def test_timeseries_frame():
    pandas = pytest.importorskip("pandas")
    sim = haff.Simulation(CONFIGS["dsmc-blocks"]).run(progress=False)
    frame = sim.timeseries_frame()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == list(sim.timeseries)
    assert len(frame) == 6


def test_rough_particles_report_their_rotational_temperature():
    """Rough particles add rotational_temperature to the time series (from rest: 0, then
    rising); smooth ones have no such column."""
    sim = haff.Simulation(CONFIGS["rough-dsmc-2d"]).run(progress=False)
    rotation = sim.timeseries["rotational_temperature"]
    assert rotation[0] == 0.0 and (rotation[1:] > 0).all()
    assert "rotational_temperature" not in haff.Simulation(CONFIGS["dsmc-blocks"]).timeseries


def test_species_timeseries_equals_species_csv(tmp_path, cli):
    """A mixture's per-species rows equal species.csv bit for bit (empty CSV fields are
    NaN), the mixture temperature is the fraction-weighted mean of the species', and a run
    without system.species has none."""
    config = {
        "system": {"dimension": 2, "particles": 600, "packing_fraction": 0.1, "seed": 4,
                   "species": [{"diameter": 1.0, "mass": 1.0, "fraction": 0.5},
                               {"diameter": 1.5, "mass": 3.0, "fraction": 0.5}]},
        "collision": {"law": "constant", "restitution": 0.8},
        "run": {"collisions_per_particle": 20.0, "samples": 5},
    }
    file = tmp_path / "mix.toml"
    file.write_text(toml_of(config))
    cli("run", str(file), "--out", str(tmp_path / "cli"))
    sim = haff.Simulation(config).run(progress=False)
    rows = sim.species_timeseries
    columns = csv_columns(tmp_path / "cli" / "species.csv")
    assert list(columns) == ["time", "collisions_per_particle", "species", "temperature",
                             "a2", "collision_frequency"]
    for name, values in columns.items():
        want = np.array([float(x) if x != "" else np.nan for x in values])
        np.testing.assert_array_equal(rows[name], want, err_msg=name)
    assert np.isnan(rows["collision_frequency"][:2]).all()
    assert (rows["collision_frequency"][2:] > 0).all()
    mixture = 0.5 * rows["temperature"][0::2] + 0.5 * rows["temperature"][1::2]
    np.testing.assert_allclose(mixture, sim.timeseries["temperature"], rtol=1e-12)
    assert haff.Simulation(CONFIGS["dsmc-blocks"]).species_timeseries is None


@pytest.mark.parametrize("name", ["event-driven", "viscoelastic-2d-by-time"])
def test_advance_in_parts_equals_one_run(name):
    whole = haff.Simulation(CONFIGS[name]).run(progress=False)
    parts = haff.Simulation(CONFIGS[name])
    stop = CONFIGS[name]["run"]
    if "end_time" in stop:
        assert parts.advance(time=1.234)
        assert parts.time == 1.234
        assert parts.advance(collisions_per_particle=parts.collisions_per_particle + 1.5)
    else:
        assert parts.advance(collisions_per_particle=7.3)
        assert parts.collisions == round(7.3 * 500 / 2)
        assert parts.advance(time=parts.time + 0.05)
    assert not parts.complete
    parts.run(progress=False)
    # The event-driven engine brings particles to the present lazily: stopping between
    # samples changes nothing.
    for key, values in whole.timeseries.items():
        np.testing.assert_array_equal(parts.timeseries[key], values, err_msg=key)


def test_advance_refuses_points_outside_the_run():
    sim = haff.Simulation(CONFIGS["event-driven"])
    with pytest.raises(haff.ConfigError, match="^collisions_per_particle: 41"):
        sim.advance(collisions_per_particle=41.0)
    sim.advance(collisions_per_particle=10.0)
    with pytest.raises(haff.ConfigError, match="^collisions_per_particle: 5"):
        sim.advance(collisions_per_particle=5.0)
    with pytest.raises(haff.ConfigError, match="^time: NaN"):
        sim.advance(time=float("nan"))
    with pytest.raises(haff.ConfigError, match="exactly one"):
        sim.advance()
    # A time beyond the end of a run stopped by collisions: the run ends first.
    assert sim.advance(time=1e9) is False and sim.complete


def test_save_and_load_continue_bit_for_bit(tmp_path, cli):
    config = CONFIGS["event-driven"]
    a = haff.Simulation(config)
    a.advance(collisions_per_particle=13.0)  # between two samples
    a.save(tmp_path / "mid.bin")
    b = haff.Simulation.load(tmp_path / "mid.bin")
    assert b.time == a.time and b.collisions == a.collisions
    np.testing.assert_array_equal(b.velocities, a.velocities)
    a.run(progress=False)
    b.run(progress=False)
    for key, values in a.timeseries.items():
        np.testing.assert_array_equal(b.timeseries[key], values, err_msg=key)
    # A check-point saved by Python into a directory resumes with `haff run --resume`, and
    # both continue the same way.
    c = haff.Simulation(config)
    c.advance(collisions_per_particle=25.0)
    out = tmp_path / "out"
    c.write(out)
    c.save(out)
    cli("run", "--resume", str(out))
    c.run(progress=False)
    assert_equals_csv(c.timeseries, out / "timeseries.csv")


def test_dense_starts_tell_their_growth(tmp_path):
    dense = {"system": {"particles": 1500, "packing_fraction": 0.55, "seed": 2},
             "collision": {"law": "constant", "restitution": 0.9},
             "run": {"collisions_per_particle": 5.0, "samples": 3}}
    a = haff.Simulation(dense)
    state = a.initial_state
    assert state["method"] == "growth" and state["start_fraction"] == 0.3
    assert state["events"] >= state["collisions"] > 0
    a.save(tmp_path / "dense.bin")
    assert haff.Simulation.load(tmp_path / "dense.bin").initial_state == state
    a.run(progress=False)
    a.write(tmp_path / "out")
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["initial_state"] == state
    assert haff.Simulation(CONFIGS["event-driven"]).initial_state is None


def test_walls_as_a_frame_like_walls_csv(tmp_path):
    boxed = {"system": {"dimension": 2, "particles": 200, "packing_fraction": 0.1, "seed": 7},
             "collision": {"law": "constant", "restitution": 1.0},
             "run": {"collisions_per_particle": 10.0, "samples": 4},
             "wall": [{"axis": "y", "side": "low", "kind": "thermal", "temperature": 2.0},
                      {"axis": "y", "side": "high", "kind": "elastic"}]}
    sim = haff.Simulation(boxed).run(progress=False)
    frame = sim.walls()
    assert list(frame.columns) == ["time", "collisions_per_particle", "axis", "side",
                                   "collisions", "momentum", "energy"]
    assert len(frame) == 2 * len(sim.timeseries["time"])
    assert set(frame["side"]) == {"low", "high"} and set(frame["axis"]) == {"y"}
    high = frame[frame["side"] == "high"]
    assert (high["energy"] == 0.0).all() and high["collisions"].iloc[-1] > 0
    sim.write(tmp_path / "out")
    csv = (tmp_path / "out" / "walls.csv").read_text().splitlines()
    assert csv[0] == "time,collisions_per_particle,axis,side,collisions,momentum,energy"
    assert len(csv) == 1 + len(frame)
    assert haff.Simulation(CONFIGS["event-driven"]).walls() is None
    with pytest.raises(haff.ConfigError, match=r"wall\[1\]\.temperature"):
        bad = dict(boxed, wall=[boxed["wall"][0], dict(boxed["wall"][1], temperature=1.0)])
        haff.Simulation(bad)


def test_profiles_as_a_frame_like_profiles_csv(tmp_path):
    boxed = {"system": {"dimension": 2, "particles": 200, "packing_fraction": 0.1, "seed": 7},
             "collision": {"law": "constant", "restitution": 1.0},
             "run": {"collisions_per_particle": 10.0, "samples": 4},
             "output": {"profiles": {"axis": "y", "bins": 8}},
             "wall": [{"axis": "y", "side": "low", "kind": "elastic"},
                      {"axis": "y", "side": "high", "kind": "elastic"}]}
    sim = haff.Simulation(boxed).run(progress=False)
    frame = sim.profiles()
    header = ("time,collisions_per_particle,position,density,packing_fraction,temperature,"
              "temperature_x,temperature_y,temperature_z,velocity_x,velocity_y,velocity_z")
    assert list(frame.columns) == header.split(",")
    assert len(frame) == 8 * len(sim.timeseries["time"])
    # Every particle in one slab: the densities times the slab volumes sum to N.
    side = (200 * np.pi / 4 / 0.1) ** 0.5
    for _, sample in frame.groupby("time"):
        assert sample["density"].sum() * side * side / 8 == pytest.approx(200, rel=1e-12)
    assert frame["temperature_z"].isna().all() and frame["velocity_z"].isna().all()
    sim.write(tmp_path / "out")
    csv = (tmp_path / "out" / "profiles.csv").read_text().splitlines()
    assert csv[0] == header and len(csv) == 1 + len(frame)
    assert haff.Simulation(CONFIGS["event-driven"]).profiles() is None
    with pytest.raises(haff.ConfigError, match=r"output\.profiles\.axis"):
        haff.Simulation(dict(boxed, output={"profiles": {"axis": "z", "bins": 8}}))


def test_a_box_with_sides_of_its_own():
    """`system.box` from a dict: the disks fill the slabs of the long axis (x, 40 wide)
    of a 40 x 10 channel; giving the packing fraction too is refused naming the key."""
    channel = {"system": {"dimension": 2, "particles": 150, "box": [40.0, 10.0], "seed": 2},
               "collision": {"law": "constant", "restitution": 0.9},
               "run": {"collisions_per_particle": 5.0, "samples": 3},
               "output": {"profiles": {"axis": "x", "bins": 4}},
               "wall": [{"axis": "y", "side": "low", "kind": "elastic"},
                        {"axis": "y", "side": "high", "kind": "elastic"}]}
    frame = haff.Simulation(channel).run(progress=False).profiles()
    assert sorted(frame["position"].unique()) == [5.0, 15.0, 25.0, 35.0]
    # Four slabs per sample (samples may share a time): each 10 x 10 in area.
    for start in range(0, len(frame), 4):
        sample = frame.iloc[start:start + 4]
        assert sample["density"].sum() * 10.0 * 10.0 == pytest.approx(150, rel=1e-12)
    both = dict(channel, system=dict(channel["system"], packing_fraction=0.1))
    with pytest.raises(haff.ConfigError, match=r"system\.box"):
        haff.Simulation(both)


def test_write_gives_the_files_of_the_command(tmp_path, cli):
    config = CONFIGS["event-driven"]
    sim = haff.Simulation(config).run(progress=False)
    sim.write(tmp_path / "py")
    file = tmp_path / "gas.toml"
    file.write_text(toml_of(config))
    cli("run", str(file), "--out", str(tmp_path / "cli"))
    names = {p.name for p in (tmp_path / "py").iterdir()}
    assert names == {p.name for p in (tmp_path / "cli").iterdir()}
    for name in ["timeseries.csv", "velocity_histograms.csv"]:
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text()
    manifest = json.loads((tmp_path / "py" / "haff-run.json").read_text())
    assert manifest["state"] == "complete"
    sim.write(tmp_path / "py")  # the same run again: updated
    other = haff.Simulation(CONFIGS["dsmc-blocks"]).run(progress=False)
    with pytest.raises(haff.ConfigError, match="^dir: .*another haff run"):
        other.write(tmp_path / "py")
    other.write(tmp_path / "py", force=True)


@pytest.mark.parametrize(
    "change, key",
    [
        ({"system": {"packing_fraction": 2.0}}, "system.packing_fraction"),
        ({"system": {"particles": 1}}, "system.particles"),
        ({"system": {"temperature": float("nan")}}, "system.temperature"),
        ({"system": {"colour": "red"}}, "system"),
        ({"collision": {"restitution": 1.5}}, "collision.restitution"),
        ({"collision": {"law": "sticky"}}, "collision.law"),
        ({"run": {"samples": "many"}}, "run.samples"),
        ({"run": {"engine": "dsmc", "dsmc_scheme": "fastest"}}, "run.dsmc_scheme"),
        ({"collision": {"beta": None}}, "collision.beta"),
        ({"collision": {"law": "viscoelastic", "material": "cheese",
                        "dissipative_constant": 1e-9}}, "collision.material"),
        ({"run": {"engine": "soft-sphere"}}, "collision.law"),
        ({"collision": {"tangential_restitution": 1.5}}, "collision.tangential_restitution"),
        ({"collision": {"friction": 0.3}}, "collision.friction"),
        ({"system": {"inertia": 0.9}, "collision": {"tangential_restitution": 0.5}},
         "system.inertia"),
    ],
)
def test_bad_configs_name_the_key(change, key):
    config = json.loads(json.dumps(CONFIGS["event-driven"]))
    for section, values in change.items():
        config[section].update(values)
    with pytest.raises(haff.ConfigError) as error:
        haff.Simulation(config)
    assert isinstance(error.value, ValueError)
    assert str(error.value).startswith(key), str(error.value)


def test_bad_sources_and_files(tmp_path):
    with pytest.raises(haff.ConfigError, match="no such run file"):
        haff.Simulation("missing.toml")
    with pytest.raises(haff.ConfigError, match="<toml text>"):
        haff.Simulation("[system\nparticles = 3")
    bad = tmp_path / "bad.toml"
    bad.write_text(toml_of({"system": {"particles": 100, "packing_fraction": -1.0},
                            "collision": {"law": "constant", "restitution": 0.9},
                            "run": {"collisions_per_particle": 1.0, "samples": 2}}))
    with pytest.raises(haff.ConfigError, match=r"bad\.toml: system\.packing_fraction"):
        haff.Simulation(bad)
    with pytest.raises(haff.ConfigError, match="config"):
        haff.Simulation(42)
    damaged = tmp_path / "damaged.bin"
    sim = haff.Simulation(CONFIGS["event-driven"])
    sim.advance(collisions_per_particle=2.0)
    sim.save(damaged)
    data = bytearray(damaged.read_bytes())
    data[-5] ^= 0xFF
    damaged.write_bytes(bytes(data))
    with pytest.raises(haff.ConfigError, match="checksum"):
        haff.Simulation.load(damaged)
    with pytest.raises(haff.ConfigError, match="not a haff check-point"):
        haff.Simulation.load(bad)


LONG = {
    "system": {"particles": 4000, "packing_fraction": 0.1, "seed": 2},
    "collision": {"law": "constant", "restitution": 0.9},
    "run": {"collisions_per_particle": 400.0, "samples": 3},
}


def test_run_releases_the_gil():
    sim = haff.Simulation(LONG)
    seconds, pause = longest_pause_while(lambda: sim.advance(collisions_per_particle=150.0))
    assert seconds > 0.3, "too short to tell"
    # Between pieces the driver takes the GIL for a moment; the looping thread must never
    # wait for a large part of the run.
    assert pause < 0.25 * seconds, (pause, seconds)


def test_ctrl_c_interrupts_and_the_run_goes_on():
    sim = haff.Simulation(LONG)
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run(progress=False)
    timer.join()
    assert 0 < sim.collisions_per_particle < 400.0
    # It goes on from where it stopped, to the same end as a run never interrupted.
    sim.run(progress=False)
    whole = haff.Simulation(LONG).run(progress=False)
    for key, values in whole.timeseries.items():
        np.testing.assert_array_equal(sim.timeseries[key], values, err_msg=key)


def test_progress_callback_errors_stop_the_run():
    seen = []

    def callback(done, total, note):
        seen.append((done, total))
        if done == 2:
            raise RuntimeError("enough")

    sim = haff.Simulation(CONFIGS["event-driven"])
    with pytest.raises(RuntimeError, match="enough"):
        sim._sim.run(callback)
    assert seen[0] == (0, 9) and seen[-1] == (2, 9)
    assert len(sim.timeseries["time"]) == 2


def test_pairwise_restitution_and_driving_from_a_dict():
    """A restitution matrix and [driving] from a dict: the run heats up to its steady state,
    per species; a non-symmetric matrix names its entry."""
    config = {
        "system": {"dimension": 3, "particles": 2000, "packing_fraction": 0.1, "seed": 3,
                   "species": [{"diameter": 1.0, "mass": 1.0, "fraction": 0.5},
                               {"diameter": 1.0, "mass": 4.0, "fraction": 0.5}]},
        "collision": {"law": "constant", "restitution": [[0.9, 0.6], [0.6, 0.75]]},
        "driving": {"kind": "white-noise", "strength": 1.0},
        "run": {"engine": "dsmc", "collisions_per_particle": 10.0, "samples": 3},
    }
    sim = haff.Simulation(config).run(progress=False)
    rows = sim.species_timeseries
    assert (rows["temperature"][-2:] > 2.0).all()
    config["collision"]["restitution"] = [[0.9, 0.6], [0.5, 0.75]]
    with pytest.raises(haff.ConfigError, match=r"collision\.restitution\[0\]\[1\]"):
        haff.Simulation(config)


def test_thermostat_and_species_materials_from_a_dict():
    """The Gaussian thermostat holds the temperature in an event-driven run; species of
    their own materials collide with the beta of their pair; a species' material with
    another law names the key."""
    config = {
        "system": {"dimension": 3, "particles": 500, "packing_fraction": 0.05, "seed": 2,
                   "species": [
                       {"diameter": 1.0, "mass": 1.0, "fraction": 0.5,
                        "young": 1e5, "poisson": 0.3, "dissipative_constant": 2e-3},
                       {"diameter": 1.4, "mass": 2.744, "fraction": 0.5,
                        "young": 1e4, "poisson": 0.4, "dissipative_constant": 1e-2}]},
        "collision": {"law": "viscoelastic"},
        "driving": {"kind": "gaussian-thermostat", "temperature": 1.5},
        "run": {"engine": "event-driven", "collisions_per_particle": 5.0, "samples": 4,
                "spacing": "linear"},
    }
    sim = haff.Simulation(config).run(progress=False)
    temperature = sim.timeseries["temperature"][1:]
    # Between applications (a tenth of a mean free time) the gas cools by a few per cent.
    assert (temperature <= 1.5 + 1e-9).all() and (temperature > 1.4).all()
    config["collision"] = {"law": "constant", "restitution": 0.9}
    with pytest.raises(haff.ConfigError, match=r"system\.species\[0\]\.young"):
        haff.Simulation(config)


def test_a_sheared_gas_reports_its_pressure_tensor_and_rheology(tmp_path):
    """`[shear]` from a dict: `pressure()` is pressure.csv as a frame, `rheology()` is
    summary.json's `rheology` (the same numbers, both from sim); P_xy opposes the shear;
    a rate that is not finite is refused naming the key."""
    sheared = {"system": {"dimension": 2, "particles": 400, "packing_fraction": 0.05, "seed": 4},
               "collision": {"law": "constant", "restitution": 0.8},
               "run": {"collisions_per_particle": 40.0, "samples": 20, "spacing": "linear"},
               "shear": {"rate": 0.05}}
    sim = haff.Simulation(sheared).run(progress=False)
    frame = sim.pressure()
    assert list(frame.columns) == ["time", "collisions_per_particle", "pxx", "pyy", "pzz",
                                   "pxy", "pxz", "pyz", "kinetic_xy"]
    assert len(frame) == len(sim.timeseries["time"])
    assert (frame["pxy"].iloc[len(frame) // 2:] < 0.0).all()
    assert (frame["pzz"] == 0.0).all()
    rheology = sim.rheology()
    sim.write(tmp_path / "out")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert rheology == summary["rheology"]
    assert rheology["pxy"]["mean"] < 0.0 and rheology["viscosity"]["mean"] > 0.0
    csv = (tmp_path / "out" / "pressure.csv").read_text().splitlines()
    assert csv[0] == "time,collisions_per_particle,pxx,pyy,pzz,pxy,pxz,pyz,kinetic_xy"
    assert haff.Simulation(CONFIGS["event-driven"]).pressure() is None
    assert haff.Simulation(CONFIGS["event-driven"]).rheology() is None
    with pytest.raises(haff.ConfigError, match=r"shear\.rate"):
        haff.Simulation(dict(sheared, shear={"rate": float("nan")}))


def test_an_elastic_gas_reports_its_green_kubo_viscosity(tmp_path):
    """`output.pressure` without `[shear]`: `green_kubo()` is summary.json's `green_kubo`
    (the same numbers, both from sim), with a positive viscosity and its error; an
    inelastic gas is not at equilibrium and says so."""
    elastic = {"system": {"dimension": 3, "particles": 300, "packing_fraction": 0.1, "seed": 2},
               "collision": {"law": "constant", "restitution": 1.0},
               "run": {"end_time": 400.0, "samples": 8000, "spacing": "linear"},
               "output": {"pressure": True}}
    sim = haff.Simulation(elastic).run(progress=False)
    gk = sim.green_kubo()
    sim.write(tmp_path / "out")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert gk == summary["green_kubo"]
    assert gk["viscosity"]["mean"] > 0.0 and gk["viscosity"]["error"] > 0.0
    assert gk["batches"] >= 5
    elastic["collision"]["restitution"] = 0.9
    sim = haff.Simulation(elastic).run(progress=False)
    assert "not elastic" in sim.green_kubo()["skipped"]
    assert haff.Simulation(CONFIGS["event-driven"]).green_kubo() is None


def test_unknown_names_suggest_the_closest():
    """A misspelt key or value: the ConfigError names it and suggests the closest allowed
    name, as the CLI does (the same sim::description)."""
    config = {"system": {"particles": 10, "packing_fraction": 0.1},
              "collision": {"law": "constant", "restituton": 0.9},
              "run": {"collisions_per_particle": 1}}
    with pytest.raises(haff.ConfigError,
                       match=r"unknown key `restituton` in \[collision\]; did you mean "
                             r"`restitution`\?"):
        haff.Simulation(config)
    config["collision"] = {"law": "constnt", "restitution": 0.9}
    with pytest.raises(haff.ConfigError, match="did you mean `constant`"):
        haff.Simulation(config)
