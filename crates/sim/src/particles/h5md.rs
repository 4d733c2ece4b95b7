//! H5MD files (H5MD 1.1, www.nongnu.org/h5md/h5md.html) through the HDF5 library (the
//! feature `h5md`). The layout haff writes:
//!
//! ```text
//! h5md                         +-- version [1, 1]
//!  |-- author                  +-- name
//!  \-- creator                 +-- name "haff", version
//! particles/all
//!  |-- box                     +-- dimension, boundary ["periodic", ...]
//!  |    \-- edges              f64 [D]              (the sides; the box from the origin)
//!  |-- position/{step,time,value}   i64 [F], f64 [F], f64 [F][N][D]
//!  |-- velocity/{step,time,value}   (if the configuration has velocities)
//!  |-- angular_velocity/{step,time,value}  f64 [F][N][3] (haff's: spins; disks: z)
//!  |-- species                 i32 [N]   (indices from 0; time-independent)
//!  |-- mass                    f64 [N]   (time-independent)
//!  \-- diameter                f64 [N]   (haff's; time-independent)
//! observables/<name>/{step,time,value}   f64 [F] (what a caller appends)
//! ```
//!
//! `time` datasets are left out when the frames carry no time (H5MD 1.1 allows it). The
//! species, masses and diameters are written once: the frames appended later must have
//! the same. No `image`: haff's positions are in the box and it keeps no crossings. Frames
//! are chunks of [1][N][D] (one write and one read each), data are written as they are:
//! the round trip is bit for bit. Every series is chunked and resizable along F and the
//! file is flushed after each frame and value: a killed run leaves a valid file, which
//! [`Trajectory::resume`] cuts back to the run's check-point and continues. The reader takes what other writers put there too: time-
//! dependent or time-independent elements, scalar `step`s with an `offset`, a `box/edges`
//! matrix if diagonal, the velocities etc. of the position's step; positions are wrapped
//! into the box.

mod read;

use super::Configuration;
use crate::error::{Error, Result};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Extent, File, Group};
use ndarray::{s, ArrayView1, ArrayView2};
use std::path::{Path, PathBuf};
use std::str::FromStr;

pub(super) use read::read;

/// An HDF5 error as one line.
fn line(e: hdf5::Error) -> String {
    e.to_string().replace('\n', "; ")
}

/// A time series: its `step` (and `time`) datasets and the value dataset.
struct Series {
    step: Dataset,
    time: Option<Dataset>,
    value: Dataset,
    /// The shape of one sample.
    sample: Vec<usize>,
}

impl Series {
    fn create(group: &Group, name: &str, sample: &[usize], timed: bool) -> hdf5::Result<Self> {
        let g = group.create_group(name)?;
        let step = g
            .new_dataset::<i64>()
            .chunk(1024)
            .shape(Extent::resizable(0))
            .create("step")?;
        let time = if timed {
            Some(
                g.new_dataset::<f64>()
                    .chunk(1024)
                    .shape(Extent::resizable(0))
                    .create("time")?,
            )
        } else {
            None
        };
        let mut shape = vec![Extent::resizable(0)];
        shape.extend(sample.iter().map(|&k| Extent::fixed(k)));
        let mut chunk = vec![if sample.is_empty() { 1024 } else { 1 }];
        chunk.extend(sample.iter().map(|&k| k.max(1)));
        let value = g
            .new_dataset::<f64>()
            .chunk(chunk)
            .shape(shape)
            .create("value")?;
        Ok(Series {
            step,
            time,
            value,
            sample: sample.to_vec(),
        })
    }

    /// The series `name` of `group` as haff writes it: `step` (and `time`) one per
    /// sample, all three resizable along the sample axis (so a resumed run can cut them).
    fn open(group: &Group, name: &str) -> hdf5::Result<Self> {
        let g = group
            .group(name)
            .map_err(|_| hdf5::Error::from(format!("no group `{name}`").as_str()))?;
        let growing = |what: &str| -> hdf5::Result<Dataset> {
            let ds = g
                .dataset(what)
                .map_err(|_| hdf5::Error::from(format!("{name}: no dataset `{what}`").as_str()))?;
            if ds.is_scalar() || !ds.is_chunked() || !ds.is_resizable() {
                return Err(format!(
                    "{name}/{what}: not a resizable series (not written by haff's Trajectory)"
                )
                .as_str()
                .into());
            }
            Ok(ds)
        };
        let step = growing("step")?;
        let time = if g.link_exists("time") {
            Some(growing("time")?)
        } else {
            None
        };
        let value = growing("value")?;
        let sample = value.shape()[1..].to_vec();
        Ok(Series {
            step,
            time,
            value,
            sample,
        })
    }

    /// The number of complete samples (a crash between its datasets' writes leaves some
    /// longer than others).
    fn len(&self) -> usize {
        let mut k = self.step.shape()[0].min(self.value.shape()[0]);
        if let Some(t) = &self.time {
            k = k.min(t.shape()[0]);
        }
        k
    }

    /// Cuts the series to its first `k` samples.
    fn truncate(&self, k: usize) -> hdf5::Result<()> {
        self.step.resize(k)?;
        if let Some(t) = &self.time {
            t.resize(k)?;
        }
        let mut shape = vec![k];
        shape.extend(&self.sample);
        self.value.resize(shape)
    }

    /// Appends one sample (`data` of the sample's shape, row-major).
    fn push(&self, step: i64, time: Option<f64>, data: &[f64]) -> hdf5::Result<()> {
        let k = self.step.shape()[0];
        self.step.resize(k + 1)?;
        self.step.write_slice(&[step], k..k + 1)?;
        if let (Some(t), Some(time)) = (&self.time, time) {
            t.resize(k + 1)?;
            t.write_slice(&[time], k..k + 1)?;
        }
        let mut shape = vec![k + 1];
        shape.extend(&self.sample);
        self.value.resize(shape)?;
        match self.sample.as_slice() {
            [] => self.value.write_slice(&[data[0]], k..k + 1),
            [n, d] => {
                let view = ArrayView2::from_shape((*n, *d), data)
                    .map_err(|e| hdf5::Error::from(e.to_string().as_str()))?;
                self.value.write_slice(view, s![k, .., ..])
            }
            _ => Err("a sample of an unexpected shape".into()),
        }
    }
}

/// What the first frame laid out.
struct Layout {
    dimension: usize,
    n: usize,
    sides: Vec<f64>,
    species: Option<Vec<usize>>,
    masses: Option<Vec<f64>>,
    diameters: Option<Vec<f64>>,
    timed: bool,
    position: Series,
    velocity: Option<Series>,
    spin: Option<Series>,
}

/// An H5MD trajectory being written: [`Trajectory::create`] (or [`Trajectory::resume`]),
/// [`Trajectory::append`] frame after frame (and [`Trajectory::observable`]s),
/// [`Trajectory::close`]. It is written in place and flushed after every frame and value,
/// so that the file a killed run leaves is a valid H5MD file a resumed run can continue.
pub struct Trajectory {
    path: PathBuf,
    file: File,
    layout: Option<Layout>,
    observables: Vec<(String, Series)>,
}

impl Trajectory {
    /// Starts an H5MD file at `path` (the `h5md` group; the particles come with the first
    /// frame), replacing any file there.
    pub fn create(path: &Path) -> Result<Self> {
        Self::start(path, path)
    }

    /// Starts the file `file`; errors name `path`.
    fn start(path: &Path, file: &Path) -> Result<Self> {
        let fail = |e: hdf5::Error| Error::ParticleFile {
            path: path.to_path_buf(),
            at: "file".into(),
            message: line(e),
        };
        let file = File::create(file).map_err(fail)?;
        let header = || -> hdf5::Result<()> {
            let h5md = file.create_group("h5md")?;
            h5md.new_attr_builder()
                .with_data(&[1i32, 1])
                .create("version")?;
            let text = |g: &Group, name: &str, value: &str| -> hdf5::Result<()> {
                let v = VarLenUnicode::from_str(value).map_err(|e| e.to_string())?;
                g.new_attr::<VarLenUnicode>()
                    .shape(())
                    .create(name)?
                    .write_scalar(&v)
            };
            let author = h5md.create_group("author")?;
            let user = std::env::var("USER").unwrap_or_else(|_| "haff".into());
            text(&author, "name", &user)?;
            let creator = h5md.create_group("creator")?;
            text(&creator, "name", "haff")?;
            text(&creator, "version", env!("CARGO_PKG_VERSION"))?;
            file.flush()
        };
        header().map_err(fail)?;
        Ok(Trajectory {
            path: path.to_path_buf(),
            file,
            layout: None,
            observables: Vec::new(),
        })
    }

    /// Reopens the trajectory a killed run left at `path` to continue it from a
    /// check-point that had written `frames` frames and, of each observable `(name,
    /// count)`, `count` values: what was appended after is cut off (observables not
    /// listed are cut to none). `c` is the run's configuration: the file must be haff's,
    /// of its dimension, number of particles, box, species, masses and diameters. No
    /// file and nothing written: a new file.
    pub fn resume(
        path: &Path,
        c: &Configuration,
        frames: usize,
        observables: &[(&str, usize)],
    ) -> Result<Self> {
        let nothing = frames == 0 && observables.iter().all(|(_, k)| *k == 0);
        if nothing {
            // Also a file damaged by a kill during its first frame: nothing to keep.
            return Self::create(path);
        }
        let fail = |at: &str, message: String| Error::ParticleFile {
            path: path.to_path_buf(),
            at: at.into(),
            message,
        };
        if !path.exists() {
            return Err(fail(
                "file",
                format!("no such file; the check-point counts {frames} frames written to it"),
            ));
        }
        if frames > 0 {
            // The reader's checks (H5MD, the box's dimension, ...) and the particles of
            // the last frame kept.
            let last = read::read(path, c.dimension, frames as i64 - 1)?;
            if last.len() != c.len() {
                return Err(fail(
                    "particles/all/position",
                    format!(
                        "{} particles in the file; the run has {}",
                        last.len(),
                        c.len()
                    ),
                ));
            }
            let same = last.sides == c.sides
                && last.species == c.species
                && last.masses == c.masses
                && last.diameters == c.diameters
                && last.time.is_some()
                && last.velocities.is_some() == c.velocities.is_some()
                && last.spins.is_some() == c.spins.is_some();
            if !same {
                return Err(fail(
                    "particles/all",
                    "the box, species, masses or diameters, or which of velocities, spins \
                     and time are given, differ from the run's"
                        .into(),
                ));
            }
        }
        let file = File::open_rw(path).map_err(|e| {
            fail(
                "file",
                format!("not an HDF5 file that can be written: {}", line(e)),
            )
        })?;
        let creator = file
            .group("h5md/creator")
            .and_then(|g| g.attr("name"))
            .and_then(|a| a.read_scalar::<VarLenUnicode>())
            .map(|s| s.as_str().to_string())
            .unwrap_or_default();
        if creator != "haff" {
            return Err(fail(
                "h5md/creator",
                format!("name {creator:?}; haff continues only the trajectories it wrote"),
            ));
        }
        let layout = if frames > 0 {
            let all = file
                .group("particles/all")
                .map_err(|e| fail("particles/all", line(e)))?;
            let series = |name: &str| -> Result<Series> {
                let s = Series::open(&all, name)
                    .map_err(|e| fail(&format!("particles/all/{name}"), line(e)))?;
                if s.len() < frames {
                    return Err(fail(
                        &format!("particles/all/{name}"),
                        format!("{} frames; the check-point counts {frames}", s.len()),
                    ));
                }
                s.truncate(frames)
                    .map_err(|e| fail(&format!("particles/all/{name}"), line(e)))?;
                Ok(s)
            };
            Some(Layout {
                dimension: c.dimension,
                n: c.len(),
                sides: c.sides.clone(),
                species: c.species.clone(),
                masses: c.masses.clone(),
                diameters: c.diameters.clone(),
                timed: true,
                position: series("position")?,
                velocity: c
                    .velocities
                    .as_ref()
                    .map(|_| series("velocity"))
                    .transpose()?,
                spin: c
                    .spins
                    .as_ref()
                    .map(|_| series("angular_velocity"))
                    .transpose()?,
            })
        } else {
            // No frame kept: the particles are laid out again by the next frame.
            if file.link_exists("particles") {
                file.unlink("particles")
                    .map_err(|e| fail("particles", line(e)))?;
            }
            None
        };
        let mut kept = Vec::new();
        let names = file
            .group("observables")
            .and_then(|g| g.member_names())
            .unwrap_or_default();
        for (name, count) in observables {
            if *count > 0 && !names.iter().any(|n| n == name) {
                return Err(fail(
                    &format!("observables/{name}"),
                    format!("no such series; the check-point counts {count} values"),
                ));
            }
        }
        for name in names {
            let at = format!("observables/{name}");
            let count = observables
                .iter()
                .find(|(n, _)| *n == name)
                .map_or(0, |(_, k)| *k);
            let s = file
                .group("observables")
                .and_then(|g| Series::open(&g, &name))
                .map_err(|e| fail(&at, line(e)))?;
            if s.len() < count {
                return Err(fail(
                    &at,
                    format!("{} values; the check-point counts {count}", s.len()),
                ));
            }
            s.truncate(count).map_err(|e| fail(&at, line(e)))?;
            kept.push((name, s));
        }
        file.flush().map_err(|e| fail("file", line(e)))?;
        Ok(Trajectory {
            path: path.to_path_buf(),
            file,
            layout,
            observables: kept,
        })
    }

    /// Writes what is buffered to the file (done after every frame and value).
    pub fn flush(&self) -> Result<()> {
        self.file.flush().map_err(|e| self.fail("file", line(e)))
    }

    fn fail(&self, at: &str, message: String) -> Error {
        Error::ParticleFile {
            path: self.path.clone(),
            at: at.into(),
            message,
        }
    }

    /// Appends a frame: `configuration` at integration step `step` and time `time`.
    pub fn append(&mut self, step: u64, time: f64, configuration: &Configuration) -> Result<()> {
        self.push(step, Some(time), configuration)
    }

    /// Appends a frame; `time` None: the file's frames carry no time (all or none do).
    pub(super) fn push(&mut self, step: u64, time: Option<f64>, c: &Configuration) -> Result<()> {
        let step = i64::try_from(step)
            .map_err(|_| self.fail("step", format!("step {step}; allowed: < 2^63")))?;
        let frame = self
            .layout
            .as_ref()
            .map_or(0, |l| l.position.step.shape()[0]);
        let at = format!("frame {frame}");
        if self.layout.is_none() {
            let layout = self
                .lay_out(c, time.is_some())
                .map_err(|e| self.fail("particles/all", line(e)))?;
            self.layout = Some(layout);
        }
        let Some(l) = &self.layout else {
            unreachable!("laid out above")
        };
        let same = l.dimension == c.dimension
            && l.n == c.len()
            && l.sides == c.sides
            && l.species == c.species
            && l.masses == c.masses
            && l.diameters == c.diameters
            && l.timed == time.is_some()
            && l.velocity.is_some() == c.velocities.is_some()
            && l.spin.is_some() == c.spins.is_some();
        if !same {
            return Err(self.fail(
                &at,
                "the box, the number of particles, their species, masses and diameters, and \
                 which of velocities, spins and time are given must be those of frame 0"
                    .into(),
            ));
        }
        let d = c.dimension;
        let flat = |list: &[[f64; 3]], width: usize| -> Vec<f64> {
            let mut out = Vec::with_capacity(list.len() * width);
            for v in list {
                out.extend_from_slice(&v[..width]);
            }
            out
        };
        let write = || -> hdf5::Result<()> {
            l.position.push(step, time, &flat(&c.positions, d))?;
            if let (Some(s), Some(v)) = (&l.velocity, &c.velocities) {
                s.push(step, time, &flat(v, d))?;
            }
            if let (Some(s), Some(w)) = (&l.spin, &c.spins) {
                s.push(step, time, &flat(w, 3))?;
            }
            Ok(())
        };
        write().map_err(|e| self.fail(&at, line(e)))?;
        self.flush()
    }

    /// The particles group of the first frame `c`.
    fn lay_out(&self, c: &Configuration, timed: bool) -> hdf5::Result<Layout> {
        let (n, d) = (c.len(), c.dimension);
        let all = self.file.create_group("particles")?.create_group("all")?;
        let b = all.create_group("box")?;
        b.new_attr::<i32>()
            .shape(())
            .create("dimension")?
            .write_scalar(&(d as i32))?;
        let periodic = VarLenUnicode::from_str("periodic").map_err(|e| e.to_string())?;
        b.new_attr_builder()
            .with_data(&vec![periodic; d])
            .create("boundary")?;
        b.new_dataset_builder()
            .with_data(ArrayView1::from(&c.sides))
            .create("edges")?;
        if let Some(s) = &c.species {
            let s: Vec<i32> = s.iter().map(|&k| k as i32).collect();
            all.new_dataset_builder().with_data(&s).create("species")?;
        }
        for (name, list) in [("mass", &c.masses), ("diameter", &c.diameters)] {
            if let Some(x) = list {
                all.new_dataset_builder().with_data(x).create(name)?;
            }
        }
        let series = |name: &str, width: usize| Series::create(&all, name, &[n, width], timed);
        Ok(Layout {
            dimension: d,
            n,
            sides: c.sides.clone(),
            species: c.species.clone(),
            masses: c.masses.clone(),
            diameters: c.diameters.clone(),
            timed,
            position: series("position", d)?,
            velocity: c
                .velocities
                .as_ref()
                .map(|_| series("velocity", d))
                .transpose()?,
            spin: c
                .spins
                .as_ref()
                .map(|_| series("angular_velocity", 3))
                .transpose()?,
        })
    }

    /// Appends `value` at `step` and `time` to the time series `observables/<name>` (e.g.
    /// `temperature`), made at its first value.
    pub fn observable(&mut self, name: &str, step: u64, time: f64, value: f64) -> Result<()> {
        let at = format!("observables/{name}");
        let step = i64::try_from(step)
            .map_err(|_| self.fail(&at, format!("step {step}; allowed: < 2^63")))?;
        if !self.observables.iter().any(|(n, _)| n == name) {
            let group = match self.file.group("observables") {
                Ok(g) => Ok(g),
                Err(_) => self.file.create_group("observables"),
            };
            let series = group
                .and_then(|g| Series::create(&g, name, &[], true))
                .map_err(|e| self.fail(&at, line(e)))?;
            self.observables.push((name.to_string(), series));
        }
        let Some((_, series)) = self.observables.iter().find(|(n, _)| n == name) else {
            unreachable!("made above")
        };
        series
            .push(step, Some(time), &[value])
            .map_err(|e| self.fail(&at, line(e)))?;
        self.flush()
    }

    /// Flushes and closes the file.
    pub fn close(self) -> Result<()> {
        let Trajectory {
            path,
            file,
            layout,
            observables,
        } = self;
        // The datasets first: the file closes when its last handle does.
        drop(layout);
        drop(observables);
        file.close().map_err(|e| Error::ParticleFile {
            path,
            at: "file".into(),
            message: line(e),
        })
    }
}

/// Writes `c` as a one-frame H5MD file (step 0, its time if it has one), as
/// `path.partial` renamed at the end, as haff's other files.
pub(super) fn write(path: &Path, c: &Configuration) -> Result<()> {
    let mut partial = path.as_os_str().to_owned();
    partial.push(".partial");
    let partial = PathBuf::from(partial);
    let mut t = Trajectory::start(path, &partial)?;
    t.push(0, c.time, c)?;
    t.close()?;
    std::fs::rename(&partial, path).map_err(|e| Error::ParticleFile {
        path: path.to_path_buf(),
        at: "file".into(),
        message: e.to_string(),
    })
}

#[cfg(test)]
mod tests;
