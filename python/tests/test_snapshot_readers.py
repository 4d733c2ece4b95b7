"""The snapshots and fields of a run, opened by the community's readers (issue 38).

Kitware's `vtk` package reads the `.vtu` snapshots, the `.vti` fields and the `.pvd`
collections with its own XML readers (the `.pvd` through VTK's `vtkXMLDataParser`: the pip
package has no PVD reader, ParaView's); OVITO opens the LAMMPS dump and extended XYZ
trajectories as animations of one frame per snapshot. The run is the `haff` command's
(HAFF_BIN). Oracle for the particles: the extended XYZ trajectory parsed here by Python
(correctly rounded parsing of haff's shortest round-trip numbers), which
crates/sim/tests/snapshots.rs shows to hold the same bits as the `.vtu` of the same sample.
"""

import re

import numpy as np
import pytest

vtk_xml = pytest.importorskip("vtkmodules.vtkIOXML")
vtk_parser = pytest.importorskip("vtkmodules.vtkIOXMLParser")
numpy_support = pytest.importorskip("vtkmodules.util.numpy_support")

BOX = [10.0, 9.0, 8.0]
N = 120
GRID = 4
RUN = f"""
[system]
dimension = 3
particles = {N}
box = {BOX}
seed = 4
species = [{{ diameter = 1.0, mass = 1.0, fraction = 1 }},
           {{ diameter = 0.6, mass = 0.216, fraction = 1 }}]
[collision]
law = "constant"
restitution = 0.9
[run]
collisions_per_particle = 4
samples = 5
spacing = "linear"
[output]
snapshots = {{ every = 2, format = ["vtk", "lammps-dump", "xyz"] }}
fields = {{ every = 2, grid = {GRID} }}
"""
SNAPSHOTS = [0, 2, 4]


@pytest.fixture(scope="module")
def out(tmp_path_factory, cli):
    root = tmp_path_factory.mktemp("snapshot-readers")
    (root / "run.toml").write_text(RUN)
    cli("run", str(root / "run.toml"), "--out", str(root / "out"))
    return root / "out"


def xyz_frames(path):
    """The frames of an extended XYZ file: time, box, and a float array per property."""
    lines = path.read_text().splitlines()
    frames, i = [], 0
    while i < len(lines):
        n, comment = int(lines[i]), lines[i + 1]
        table = np.array([[float(x) for x in line.split()] for line in lines[i + 2:i + 2 + n]])
        lattice = [float(x) for x in re.search(r'Lattice="([^"]+)"', comment)[1].split()]
        frame = {"time": float(re.search(r"Time=(\S+)", comment)[1]),
                 "box": [lattice[0], lattice[4], lattice[8]]}
        fields = re.search(r"Properties=(\S+)", comment)[1].split(":")
        column = 0
        for name, width in zip(fields[0::3], fields[2::3]):
            frame[name] = table[:, column:column + int(width)].squeeze()
            column += int(width)
        frames.append(frame)
        i += n + 2
    return frames


def collection(path):
    """(timestep, file) of a `.pvd`, parsed by VTK's XML parser."""
    parser = vtk_parser.vtkXMLDataParser()
    parser.SetFileName(str(path))
    assert parser.Parse() == 1, path
    root = parser.GetRootElement()
    assert root.GetName() == "VTKFile" and root.GetAttribute("type") == "Collection"
    items = root.FindNestedElementWithName("Collection")
    return [(float(items.GetNestedElement(k).GetAttribute("timestep")),
             items.GetNestedElement(k).GetAttribute("file"))
            for k in range(items.GetNumberOfNestedElements())]


def test_vtk_reads_the_snapshots(out):
    frames = xyz_frames(out / "snapshots.xyz")
    files = collection(out / "snapshots.pvd")
    assert [f for _, f in files] == [f"snapshot_{k:06d}.vtu" for k in SNAPSHOTS]
    assert [t for t, _ in files] == [f["time"] for f in frames]
    for (_, name), frame in zip(files, frames):
        reader = vtk_xml.vtkXMLUnstructuredGridReader()
        reader.SetFileName(str(out / name))
        reader.Update()
        grid = reader.GetOutput()
        assert grid.GetNumberOfPoints() == N == grid.GetNumberOfCells()
        points = numpy_support.vtk_to_numpy(grid.GetPoints().GetData())
        np.testing.assert_array_equal(points, frame["pos"], err_msg=name)
        data = grid.GetPointData()
        for array, key in (("velocity", "velo"), ("radius", "radius"), ("mass", "mass")):
            np.testing.assert_array_equal(numpy_support.vtk_to_numpy(data.GetArray(array)),
                                          frame[key], err_msg=f"{name} {array}")
        species = numpy_support.vtk_to_numpy(data.GetArray("species"))
        np.testing.assert_array_equal(species + 1, frame["type"])
        assert set(species) == {0, 1}
        box = numpy_support.vtk_to_numpy(grid.GetFieldData().GetArray("box"))
        np.testing.assert_array_equal(box, BOX)
        assert frame["box"] == BOX


def test_vtk_reads_the_fields(out):
    """The density is a number per cell volume: over the cells it sums to N (the cell
    volume from the box; the `.vti`'s spacing is float32, to 1 float32 ulp)."""
    files = collection(out / "fields.pvd")
    assert [f for _, f in files] == [f"fields_{k:06d}.vti" for k in SNAPSHOTS]
    cell = np.prod(BOX) / GRID ** 3
    for _, name in files:
        reader = vtk_xml.vtkXMLImageDataReader()
        reader.SetFileName(str(out / name))
        reader.Update()
        image = reader.GetOutput()
        assert image.GetDimensions() == (GRID + 1,) * 3
        np.testing.assert_allclose(image.GetSpacing(), np.array(BOX) / GRID, rtol=2.0 ** -23)
        density = numpy_support.vtk_to_numpy(image.GetCellData().GetArray("density"))
        assert density.shape == (GRID ** 3,)
        assert density.sum() * cell == pytest.approx(N, rel=1e-12)
        for array in ("velocity", "temperature", "vorticity"):
            assert image.GetCellData().GetArray(array).GetNumberOfTuples() == GRID ** 3


def test_ovito_opens_the_trajectories(out):
    """OVITO's text parser is within 2 ulp (1e-15 relative: test_particles.py)."""
    import_file = pytest.importorskip("ovito.io").import_file
    frames = xyz_frames(out / "snapshots.xyz")
    for name, ovito_format in (("snapshots.lammpstrj", "lammps/dump"), ("snapshots.xyz", None)):
        path = str(out / name)
        pipeline = (import_file(path, input_format=ovito_format) if ovito_format
                    else import_file(path))
        assert pipeline.num_frames == len(SNAPSHOTS), name
        for k, frame in enumerate(frames):
            data = pipeline.compute(k)
            assert data.particles.count == N
            np.testing.assert_allclose(np.diag(np.asarray(data.cell[:3, :3])), BOX, rtol=1e-15)
            np.testing.assert_allclose(np.asarray(data.particles["Position"][...]), frame["pos"],
                                       rtol=1e-15, atol=1e-15, err_msg=f"{name} frame {k}")
            np.testing.assert_array_equal(np.asarray(data.particles["Particle Type"][...]),
                                          frame["type"])


def test_haff_reads_the_trajectories_back(out):
    """`haff.read_configuration` (any frame, -1 the last) finds the frames parsed here; a
    package with the `vtk` format reads the `.vtu` to the same bits. Unchecked: spheres of
    an event-driven run touch to rounding (overlaps of 1e-16 that the check refuses)."""
    haff = pytest.importorskip("haff")
    frames = xyz_frames(out / "snapshots.xyz")
    for k, frame in enumerate(frames):
        for name, format in (("snapshots.xyz", "xyz"), ("snapshots.lammpstrj", "lammps-dump")):
            c = haff.read_configuration(out / name, format, frame=k, check=False)
            np.testing.assert_array_equal(c["positions"], frame["pos"], err_msg=f"{name} {k}")
            np.testing.assert_array_equal(c["box"], BOX)
    last = haff.read_configuration(out / "snapshots.xyz", "xyz", check=False)
    assert last["time"] == frames[-1]["time"]
    try:
        vtu = haff.read_configuration(out / "snapshot_000004.vtu", "vtk", check=False)
    except haff.ConfigError as e:
        pytest.skip(f"the installed package predates the vtk format: {e}")
    np.testing.assert_array_equal(vtu["positions"], frames[-1]["pos"])
    np.testing.assert_array_equal(vtu["box"], BOX)


def test_python_runs_write_the_same_trajectories(out, tmp_path):
    """haff.Simulation with the format list of the run file writes the command's files byte
    for byte; snapshot_files() names the `.vtu` (with "vtk"), else the trajectory."""
    haff = pytest.importorskip("haff")
    config = pytest.importorskip("tomllib").loads(RUN)
    sim = haff.Simulation(config, output_dir=tmp_path / "py")
    sim.run(progress=False)
    sim.write()
    for name in ("snapshots.xyz", "snapshots.lammpstrj", "snapshot_000004.vtu", "snapshots.pvd"):
        assert (tmp_path / "py" / name).read_bytes() == (out / name).read_bytes(), name
    assert [p.name for _, p in sim.snapshot_files()] == [
        f"snapshot_{k:06d}.vtu" for k in SNAPSHOTS]
    config["output"]["snapshots"]["format"] = "xyz"
    sim = haff.Simulation(config, output_dir=tmp_path / "xyz")
    sim.run(progress=False)
    assert [p.name for _, p in sim.snapshot_files()] == ["snapshots.xyz"] * len(SNAPSHOTS)
    assert (tmp_path / "xyz" / "snapshots.xyz").read_bytes() == \
        (out / "snapshots.xyz").read_bytes()


def test_a_vtu_without_its_box_needs_the_box(out, tmp_path):
    """A `.vtu` whose box field data is taken out reads only with `box` given (then the
    same bits); a box that differs from the file's is refused."""
    haff = pytest.importorskip("haff")
    text = (out / "snapshot_000002.vtu").read_text()
    bare = tmp_path / "bare.vtu"
    bare.write_text(re.sub(r"<FieldData>.*?</FieldData>", "", text))
    try:
        with pytest.raises(haff.ConfigError, match=r"bare\.vtu: box: .*give its sides"):
            haff.read_configuration(bare, "vtk", check=False)
        c = haff.read_configuration(bare, "vtk", check=False, box=BOX)
    except TypeError as e:
        pytest.skip(f"the installed package predates read_configuration(box=...): {e}")
    whole = haff.read_configuration(out / "snapshot_000002.vtu", "vtk", check=False)
    for key in whole:
        np.testing.assert_array_equal(c[key], whole[key], err_msg=key)
    with pytest.raises(haff.ConfigError, match="box.*differs"):
        haff.read_configuration(out / "snapshot_000002.vtu", "vtk", check=False, box=[1, 2, 3])
