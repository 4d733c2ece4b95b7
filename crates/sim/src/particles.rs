//! Particle files in and out (issue 38): a [`Configuration`] — the box and every particle's
//! position, and what the file has of velocities, diameters, masses, species and spins —
//! read from and written to the formats the community's tools read: `csv` (haff's columns),
//! `lammps-dump` (a `dump custom` frame), `xyz` (extended XYZ with a `Lattice`), `vtk`
//! (the `.vtu` of haff's snapshots), `lammps-data` (a data file of `atom_style sphere`),
//! `h5md` (H5MD, with the feature `h5md`).
//!
//! Reading checks everything a run needs before it starts ([`Configuration::check`]):
//! finite numbers, particles inside the box, no two spheres overlapping (the first pair
//! named with its overlap), diameters and masses > 0. Every error names the file, the line
//! or record, and the field ([`Error::ParticleFile`]).
//!
//! The box is periodic, its lower corner at the origin: a file whose box starts elsewhere
//! (LAMMPS' `xlo`) has its positions shifted by the lower corner when read.

mod csv;
#[cfg(feature = "h5md")]
mod h5md;
mod lammps;
mod lammps_data;
mod overlaps;
mod vtu;
mod xyz;

use crate::error::{Error, Result};
use std::path::Path;

#[cfg(feature = "h5md")]
pub use h5md::Trajectory;
pub use overlaps::first_overlap;

/// A vector of up to three components (the unused ones 0).
pub type Vec3 = [f64; 3];

/// The formats of particle files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `x,y[,z],vx,vy[,vz]` and optional `diameter,mass,species,wx,wy,wz` columns, a header
    /// line first; the box on a first comment line `# box = Lx Ly [Lz]`.
    Csv,
    /// A LAMMPS `dump custom` text file: `ITEM: TIMESTEP`, `NUMBER OF ATOMS`, `BOX BOUNDS`,
    /// `ATOMS id x y z vx vy vz radius|diameter [mass type omegax omegay omegaz]`.
    LammpsDump,
    /// Extended XYZ: the count, a comment line with `Lattice="..."` (orthogonal) and
    /// `Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1`, then the particles.
    Xyz,
    /// The VTK XML unstructured grid of haff's snapshots (`snapshot_NNNNNN.vtu`): points,
    /// point data `radius`, `mass`, `velocity`, `species`, `angular_velocity`, and the box
    /// as field data `box` (a `.vtu` without it is read only with the sides given).
    Vtk,
    /// A LAMMPS data file of `atom_style sphere` (`read_data`, `write_data`): header, `Atoms
    /// # sphere` (id type diameter density x y z), `Velocities` (id v omega).
    LammpsData,
    /// H5MD 1.1 (HDF5): `particles/all/{box,position,velocity,...}`; frames of a
    /// trajectory ([`Trajectory`] with the feature `h5md`; without it an error says how to
    /// build haff with it).
    H5md,
}

impl Format {
    /// The names of the formats, as a run file spells them.
    pub const NAMES: [&'static str; 6] =
        ["csv", "lammps-dump", "xyz", "vtk", "lammps-data", "h5md"];

    /// The name a run file spells.
    pub fn name(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::LammpsDump => "lammps-dump",
            Format::Xyz => "xyz",
            Format::Vtk => "vtk",
            Format::LammpsData => "lammps-data",
            Format::H5md => "h5md",
        }
    }

    /// The format a file's extension names, if it names one: `.csv`; `.dump`, `.lammpstrj`;
    /// `.xyz`, `.extxyz`; `.vtu`; `.data`, `.lmp`; `.h5md`, `.h5`.
    pub fn of_extension(path: &Path) -> Option<Self> {
        match path.extension()?.to_str()? {
            "csv" => Some(Format::Csv),
            "dump" | "lammpstrj" => Some(Format::LammpsDump),
            "xyz" | "extxyz" => Some(Format::Xyz),
            "vtu" => Some(Format::Vtk),
            "data" | "lmp" => Some(Format::LammpsData),
            "h5md" | "h5" => Some(Format::H5md),
            _ => None,
        }
    }

    /// The format named `name` (one of [`Format::NAMES`]), or an error naming `key`.
    pub fn parse(key: &str, name: &str) -> Result<Self> {
        match name {
            "csv" => Ok(Format::Csv),
            "lammps-dump" => Ok(Format::LammpsDump),
            "xyz" => Ok(Format::Xyz),
            "vtk" => Ok(Format::Vtk),
            "lammps-data" => Ok(Format::LammpsData),
            "h5md" => Ok(Format::H5md),
            other => Err(Error::input(
                key,
                format!(
                    "`{other}` is not a particle file format; allowed: {}",
                    Format::NAMES.join(", ")
                ),
            )),
        }
    }
}

/// Particles as a file holds them: the box (periodic, from the origin), positions, and
/// what the file has of the rest (None: the file has no such column).
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration {
    /// 1, 2 or 3.
    pub dimension: usize,
    /// The box's sides, one per dimension.
    pub sides: Vec<f64>,
    pub positions: Vec<Vec3>,
    pub velocities: Option<Vec<Vec3>>,
    pub diameters: Option<Vec<f64>>,
    pub masses: Option<Vec<f64>>,
    /// Species indices from 0.
    pub species: Option<Vec<usize>>,
    /// Angular velocities (rough spheres; disks: the z component).
    pub spins: Option<Vec<Vec3>>,
    /// The time the file records (LAMMPS' timestep, XYZ's `Time=`), if any.
    pub time: Option<f64>,
}

impl Configuration {
    /// The number of particles.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The diameter of particle `i` (1 where the file gives none).
    pub fn diameter(&self, i: usize) -> f64 {
        self.diameters.as_ref().map_or(1.0, |d| d[i])
    }

    /// Checks what a run needs of the configuration, naming `path` and the record (particle
    /// index from 0) of the first fault: sides finite and > 0; positions, velocities and
    /// spins finite; positions inside the box [0, L); diameters and masses finite and > 0;
    /// no two spheres overlapping (with the diameters; `points`: skipped, for DSMC's point
    /// particles).
    pub fn check(&self, path: &Path, points: bool) -> Result<()> {
        let fail = |at: String, message: String| Error::ParticleFile {
            path: path.to_path_buf(),
            at,
            message,
        };
        if !(1..=3).contains(&self.dimension) || self.sides.len() != self.dimension {
            return Err(fail(
                "box".into(),
                format!(
                    "{} sides for dimension {}; allowed: one side per dimension, 1 ..= 3",
                    self.sides.len(),
                    self.dimension
                ),
            ));
        }
        if let Some(k) = self.sides.iter().position(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(fail(
                "box".into(),
                format!("side {k} = {} is not a finite number > 0", self.sides[k]),
            ));
        }
        let n = self.len();
        if n < 2 {
            return Err(fail(
                "particles".into(),
                format!("{n} particles; allowed: at least 2"),
            ));
        }
        let lengths = [
            ("velocities", self.velocities.as_ref().map(Vec::len)),
            ("diameters", self.diameters.as_ref().map(Vec::len)),
            ("masses", self.masses.as_ref().map(Vec::len)),
            ("species", self.species.as_ref().map(Vec::len)),
            ("spins", self.spins.as_ref().map(Vec::len)),
        ];
        for (what, len) in lengths {
            if let Some(len) = len.filter(|&l| l != n) {
                return Err(fail(what.into(), format!("{len} values for {n} particles")));
            }
        }
        let d = self.dimension;
        for (i, p) in self.positions.iter().enumerate() {
            for (k, (&x, &l)) in p.iter().zip(&self.sides).enumerate() {
                if !(x.is_finite() && (0.0..l).contains(&x)) {
                    return Err(fail(
                        format!("record {i}"),
                        format!(
                            "position {} = {x} is outside the box [0, {l})",
                            ["x", "y", "z"][k]
                        ),
                    ));
                }
            }
        }
        for (what, list) in [("velocity", &self.velocities), ("spin", &self.spins)] {
            if let Some(list) = list {
                if let Some(i) = list
                    .iter()
                    .position(|v| v[..d].iter().any(|x| !x.is_finite()))
                {
                    return Err(fail(
                        format!("record {i}"),
                        format!("{what} {:?} is not finite", &list[i][..d]),
                    ));
                }
            }
        }
        for (what, list) in [("diameter", &self.diameters), ("mass", &self.masses)] {
            if let Some(list) = list {
                if let Some(i) = list.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
                    return Err(fail(
                        format!("record {i}"),
                        format!("{what} = {} is not a finite number > 0", list[i]),
                    ));
                }
            }
        }
        if !points {
            if let Some((i, j, overlap)) = first_overlap(self) {
                return Err(fail(
                    format!("records {i} and {j}"),
                    format!(
                        "the spheres overlap by {overlap:e} (of the sum of their radii {}): \
                         allowed: no overlap",
                        0.5 * (self.diameter(i) + self.diameter(j))
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Reads frame `frame` (0 the first, -1 the last) of the particle file `path` of `format`
/// in `dimension` dimensions, without checking it ([`Configuration::check`]).
pub fn read(path: &Path, format: Format, dimension: usize, frame: i64) -> Result<Configuration> {
    read_with_box(path, format, dimension, frame, None)
}

/// [`read`], with the box's `sides` for a file that holds none (a `.vtu` not written by
/// haff); a box the file holds must agree with them.
pub fn read_with_box(
    path: &Path,
    format: Format,
    dimension: usize,
    frame: i64,
    sides: Option<&[f64]>,
) -> Result<Configuration> {
    with_box(path, read_unboxed(path, format, dimension, frame)?, sides)
}

/// [`read`], its box left empty if the file holds none (the caller supplies it:
/// `system.box` for `system.initial`).
pub fn read_unboxed(
    path: &Path,
    format: Format,
    dimension: usize,
    frame: i64,
) -> Result<Configuration> {
    if format == Format::H5md {
        return read_h5md(path, dimension, frame);
    }
    let text = std::fs::read_to_string(path).map_err(|e| Error::ParticleFile {
        path: path.to_path_buf(),
        at: "file".into(),
        message: e.to_string(),
    })?;
    let fail = |at: String, message: String| Error::ParticleFile {
        path: path.to_path_buf(),
        at,
        message,
    };
    match format {
        Format::Csv => csv::parse(&text, dimension),
        Format::LammpsDump => lammps::parse_dump(&text, dimension, frame),
        Format::Xyz => xyz::parse(&text, dimension, frame),
        Format::Vtk => vtu::parse(&text, dimension, frame),
        Format::LammpsData => lammps_data::parse_data(&text, dimension, frame),
        Format::H5md => unreachable!("read above"),
    }
    .map_err(|(at, m)| fail(at, m))
}

/// `c` with the box's `sides` for a file that holds none; a box the file holds must agree
/// with them.
fn with_box(path: &Path, mut c: Configuration, sides: Option<&[f64]>) -> Result<Configuration> {
    let fail = |at: String, message: String| Error::ParticleFile {
        path: path.to_path_buf(),
        at,
        message,
    };
    match sides {
        Some(given) if c.sides.is_empty() => c.sides = given.to_vec(),
        Some(given) if c.sides != given => {
            return Err(fail(
                "box".into(),
                format!(
                    "the file's box {:?} differs from the sides given {given:?}",
                    c.sides
                ),
            ))
        }
        None if c.sides.is_empty() => {
            return Err(fail(
                "box".into(),
                "the file holds no box: give its sides".into(),
            ))
        }
        _ => {}
    }
    Ok(c)
}

#[cfg(feature = "h5md")]
fn read_h5md(path: &Path, dimension: usize, frame: i64) -> Result<Configuration> {
    h5md::read(path, dimension, frame)
}

#[cfg(not(feature = "h5md"))]
fn read_h5md(path: &Path, _: usize, _: i64) -> Result<Configuration> {
    Err(without_h5md(path))
}

/// The error of H5MD files in a haff built without the feature `h5md`.
#[cfg_attr(feature = "h5md", allow(dead_code))]
fn without_h5md(path: &Path) -> Error {
    Error::ParticleFile {
        path: path.to_path_buf(),
        at: "format `h5md`".into(),
        message: "this haff was built without H5MD support; build it with the cargo feature \
                  `h5md` (the HDF5 library: apt-get install libhdf5-dev pkg-config; then \
                  cargo build --release --features h5md, or for Python \
                  MATURIN_PEP517_ARGS=\"--features h5md\" pip install ./python)"
            .into(),
    }
}

/// Writes `configuration` to `path` in `format` (atomically, numbers in the shortest form
/// that reads back to the same bits; `vtk`: binary f64 arrays, the time not kept).
pub fn write(path: &Path, format: Format, configuration: &Configuration) -> Result<()> {
    if format == Format::H5md {
        #[cfg(feature = "h5md")]
        return h5md::write(path, configuration);
        #[cfg(not(feature = "h5md"))]
        return Err(without_h5md(path));
    }
    let text = |write: fn(&mut dyn std::io::Write, &Configuration) -> std::io::Result<()>| {
        crate::output::write_file(path, |out| write(out, configuration))
    };
    match format {
        Format::Csv => text(csv::write),
        Format::LammpsDump => text(|out, c| lammps::write_dump(out, c, 0)),
        Format::Xyz => text(xyz::write),
        Format::LammpsData => text(lammps_data::write_data),
        Format::Vtk => vtu::write(path, configuration),
        Format::H5md => unreachable!("written above"),
    }
}

/// One LAMMPS `dump custom` frame of `c` at `timestep` (a frame of a snapshot trajectory).
pub(crate) fn write_lammps_frame(
    out: &mut dyn std::io::Write,
    c: &Configuration,
    timestep: u64,
) -> std::io::Result<()> {
    lammps::write_dump(out, c, timestep)
}

/// One extended XYZ frame of `c` (a frame of a snapshot trajectory).
pub(crate) fn write_xyz_frame(
    out: &mut dyn std::io::Write,
    c: &Configuration,
) -> std::io::Result<()> {
    xyz::write(out, c)
}

/// Parses a number of a text format, naming the line and column when it is not one.
pub(crate) fn number(text: &str, line: usize, column: &str) -> std::result::Result<f64, Fault> {
    text.parse::<f64>().map_err(|_| {
        (
            format!("line {line}"),
            format!("column `{column}`: `{text}` is not a number"),
        )
    })
}

/// Particle `i`'s columns as the LAMMPS dump and extended XYZ writers both order them,
/// each after a space: position (3), velocity (3, if any), radius, mass (if any), spin (3,
/// if any).
pub(crate) fn push_columns(row: &mut String, c: &Configuration, i: usize) {
    let mut push = |x: f64| {
        row.push(' ');
        row.push_str(&crate::output::number(x));
    };
    c.positions[i].iter().for_each(|&x| push(x));
    if let Some(v) = &c.velocities {
        v[i].iter().for_each(|&x| push(x));
    }
    push(0.5 * c.diameter(i));
    if let Some(m) = &c.masses {
        push(m[i]);
    }
    if let Some(w) = &c.spins {
        w[i].iter().for_each(|&x| push(x));
    }
}

/// The names of the columns [`push_columns`] writes, from `names` (position, velocity,
/// radius, mass, spin) joined by `separator`.
pub(crate) fn column_names(c: &Configuration, names: [&str; 5], separator: &str) -> String {
    let given = [
        true,
        c.velocities.is_some(),
        true,
        c.masses.is_some(),
        c.spins.is_some(),
    ];
    let present: Vec<&str> = names
        .iter()
        .zip(given)
        .filter(|(_, g)| *g)
        .map(|(n, _)| *n)
        .collect();
    present.join(separator)
}

/// The index of frame `frame` (from 0; negative from the end) among `count`, or a fault.
pub(crate) fn frame_index(frame: i64, count: usize) -> std::result::Result<usize, Fault> {
    let count = count as i64;
    let index = if frame < 0 { count + frame } else { frame };
    if (0..count).contains(&index) {
        Ok(index as usize)
    } else {
        Err((
            "frame".into(),
            format!(
                "frame {frame} of a file of {count} frames; allowed: -{count} ..= {}",
                count - 1
            ),
        ))
    }
}

/// Where (`line 12`, `record 3`) and what went wrong in a file.
pub(crate) type Fault = (String, String);

#[cfg(test)]
mod tests;
