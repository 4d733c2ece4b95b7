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
        SnapshotFormat::Vtk => None,
        SnapshotFormat::LammpsDump => Some(("snapshots.lammpstrj", particles::write_lammps_frame)),
        SnapshotFormat::Xyz => Some(("snapshots.xyz", |out, c, _| {
            particles::write_xyz_frame(out, c)
        })),
    }
}

/// The trajectory file of `format`, None for one file per snapshot (`vtk`).
pub fn trajectory_name(format: SnapshotFormat) -> Option<&'static str> {
    trajectory(format).map(|(name, _)| name)
}

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
        let Some((name, frame)) = trajectory(format) else {
            let path = dir.join(vtu_name(snapshot.sample));
            write_particles(&path, snapshot.system, &snapshot.data)?;
            continue;
        };
        let c = configuration.get_or_insert_with(|| configuration_of(snapshot));
        let at = match trajectories.iter().position(|(n, _)| n == name) {
            Some(k) => k,
            None => {
                trajectories.push((name.to_string(), 0));
                trajectories.len() - 1
            }
        };
        let (path, from) = (dir.join(name), trajectories[at].1);
        trajectories[at].1 = append(&path, from, |out| frame(out, c, snapshot.sample as u64))?;
    }
    Ok(())
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
