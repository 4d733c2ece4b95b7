//! The particle snapshots of `output.snapshots`, in each format asked for: `vtk`, one
//! `snapshot_NNNNNN.vtu` per snapshot (with `snapshots.pvd`, written by `crate::space`);
//! `lammps-dump` and `xyz`, one trajectory file each (`snapshots.lammpstrj`,
//! `snapshots.xyz`) with a frame per snapshot, written by the writers of
//! [`crate::particles`], so that its readers (and OVITO) read them back.
//!
//! A trajectory grows by appending; its length after every frame is kept in the records of
//! check-points, and each frame is written from that length on (the file cut there first):
//! a run resumed from a check-point continues its trajectories exactly as the run that was
//! not interrupted, whatever frames it had written after the check-point. Resumed into
//! another directory, it starts them there with the frames from the check-point on.

use crate::description::{SnapshotFormat, SnapshotFormats};
use crate::error::{Error, Result};
use crate::particles::{self, Configuration};
use crate::vtk::{write_particles, ParticleData};
use gas::system::System;
use std::io::{Seek, SeekFrom, Write};
use std::path::Path;

/// Writes one frame of a trajectory: the configuration and the sample's number.
type FrameWriter = fn(&mut dyn Write, &Configuration, u64) -> std::io::Result<()>;

/// The trajectory file of `format` and its frame writer; None for one file per snapshot
/// (`vtk`).
fn trajectory(format: SnapshotFormat) -> Option<(&'static str, FrameWriter)> {
    match format {
        SnapshotFormat::Vtk | SnapshotFormat::H5md => None,
        SnapshotFormat::LammpsDump => Some(("snapshots.lammpstrj", particles::write_lammps_frame)),
        SnapshotFormat::Xyz => Some(("snapshots.xyz", |out, c, _| {
            particles::write_xyz_frame(out, c)
        })),
    }
}

/// The trajectory file of `format`, None for one file per snapshot (`vtk`).
pub fn trajectory_name(format: SnapshotFormat) -> Option<&'static str> {
    match format {
        SnapshotFormat::H5md => Some(H5MD_NAME),
        _ => trajectory(format).map(|(name, _)| name),
    }
}

/// The H5MD trajectory's file; its entry in the records counts frames, not bytes.
const H5MD_NAME: &str = "snapshots.h5md";

/// The `.vtu` of snapshot `sample` (the sample's number, from 0).
pub fn vtu_name(sample: usize) -> String {
    format!("snapshot_{sample:06}.vtu")
}

/// The file a snapshot is recorded under (`SpaceRecords::snapshots`, the `.pvd`): its
/// `.vtu` if `vtk` is asked for, else the trajectory of the first format.
pub fn record_name(formats: &SnapshotFormats, sample: usize) -> String {
    match formats.list().iter().find_map(|&f| trajectory_name(f)) {
        Some(name) if !formats.has(SnapshotFormat::Vtk) => name.to_string(),
        _ => vtu_name(sample),
    }
}

/// One snapshot: the state and what the engine knows besides.
pub struct Snapshot<'a, const D: usize> {
    pub sample: usize,
    pub time: f64,
    pub system: &'a System<D>,
    pub data: ParticleData<'a>,
    /// The energy dissipated since the start (an observable of H5MD trajectories).
    pub energy_lost: f64,
}

/// Writes `snapshot` into `dir` in every format of `formats`; `trajectories` holds (file
/// name, bytes) of each trajectory after its last frame, and is brought up to date.
pub fn write<const D: usize>(
    dir: &Path,
    formats: &SnapshotFormats,
    snapshot: &Snapshot<'_, D>,
    trajectories: &mut Vec<(String, u64)>,
) -> Result<()> {
    let mut configuration = None;
    for &format in formats.list() {
        if format == SnapshotFormat::H5md {
            let c = configuration.get_or_insert_with(|| configuration_of(snapshot));
            let at = entry(trajectories, H5MD_NAME);
            let path = dir.join(H5MD_NAME);
            trajectories[at].1 = h5md_frame(&path, trajectories[at].1, c, snapshot)?;
            continue;
        }
        let Some((name, frame)) = trajectory(format) else {
            let path = dir.join(vtu_name(snapshot.sample));
            write_particles(&path, snapshot.system, &snapshot.data)?;
            continue;
        };
        let c = configuration.get_or_insert_with(|| configuration_of(snapshot));
        let at = entry(trajectories, name);
        let (path, from) = (dir.join(name), trajectories[at].1);
        trajectories[at].1 = append(&path, from, |out| frame(out, c, snapshot.sample as u64))?;
    }
    Ok(())
}

/// The index of the trajectory `name` in `trajectories`, added with length 0 if absent.
fn entry(trajectories: &mut Vec<(String, u64)>, name: &str) -> usize {
    match trajectories.iter().position(|(n, _)| n == name) {
        Some(k) => k,
        None => {
            trajectories.push((name.to_string(), 0));
            trajectories.len() - 1
        }
    }
}

/// Appends `snapshot` to the H5MD trajectory `path` holding `frames` frames by the records
/// (cut back to them first: frames a run wrote after its last check-point), with the
/// observables `temperature` (sum m v^2 / (N D)) and `energy_lost`, one value per frame;
/// returns the frames after it. The step is the sample's number.
#[cfg(feature = "h5md")]
fn h5md_frame<const D: usize>(
    path: &Path,
    frames: u64,
    c: &Configuration,
    snapshot: &Snapshot<'_, D>,
) -> Result<u64> {
    // A missing file: a run resumed into another directory, its trajectory there
    // beginning now (as its text trajectories and `.vtu` files do).
    let n = if path.exists() { frames as usize } else { 0 };
    let mut file = match n {
        0 => particles::Trajectory::create(path)?,
        _ => particles::Trajectory::resume(path, c, n, &[("temperature", n), ("energy_lost", n)])?,
    };
    let (step, time) = (snapshot.sample as u64, snapshot.time);
    file.append(step, time, c)?;
    let temperature = gas::observe::temperature(snapshot.system);
    file.observable("temperature", step, time, temperature)?;
    file.observable("energy_lost", step, time, snapshot.energy_lost)?;
    file.close()?;
    Ok(n as u64 + 1)
}

#[cfg(not(feature = "h5md"))]
fn h5md_frame<const D: usize>(
    path: &Path,
    _: u64,
    c: &Configuration,
    _: &Snapshot<'_, D>,
) -> Result<u64> {
    // Validation refuses the format first; this is the same message for a plan built
    // another way.
    particles::write(path, particles::Format::H5md, c).map(|_| 0)
}

/// The particles of `snapshot` as the particle files hold them (the species, spins and
/// time; collisions and bath temperatures are for the `.vtu` only).
fn configuration_of<const D: usize>(snapshot: &Snapshot<'_, D>) -> Configuration {
    let s = snapshot.system;
    let padded =
        |v: &[f64; D]| -> [f64; 3] { std::array::from_fn(|a| if a < D { v[a] } else { 0.0 }) };
    Configuration {
        dimension: D,
        sides: s.sides.to_vec(),
        positions: s.positions.iter().map(padded).collect(),
        velocities: Some(s.velocities.iter().map(padded).collect()),
        diameters: Some(s.radii.iter().map(|r| 2.0 * r).collect()),
        masses: Some(s.masses.clone()),
        species: Some(snapshot.data.species.iter().map(|&k| k as usize).collect()),
        spins: snapshot.data.angular_velocities.map(<[_]>::to_vec),
        time: Some(snapshot.time),
    }
}

/// Writes a frame into `path` from byte `from` on (the file cut there first) and returns
/// the file's length after it. A file shorter than `from` was changed since the frames
/// before were written: refused, naming it. A missing file is started afresh (a run
/// resumed into another directory: its trajectories there begin at the check-point, as
/// its `.vtu` files do).
fn append(
    path: &Path,
    from: u64,
    frame: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<u64> {
    let fail = |e| Error::write(path, e);
    let from = if path.try_exists().map_err(fail)? {
        from
    } else {
        0
    };
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .open(path)
        .map_err(fail)?;
    let length = file.metadata().map_err(fail)?.len();
    if length < from {
        return Err(Error::input(
            "output.snapshots",
            format!(
                "{}: {length} bytes where the run's records say {from}: the trajectory was \
                 changed since its last frame; start the run afresh",
                path.display()
            ),
        ));
    }
    file.set_len(from).map_err(fail)?;
    file.seek(SeekFrom::Start(from)).map_err(fail)?;
    let mut out = std::io::BufWriter::new(file);
    frame(&mut out).map_err(fail)?;
    let mut file = out.into_inner().map_err(|e| fail(e.into_error()))?;
    file.stream_position().map_err(fail)
}
