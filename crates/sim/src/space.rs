//! The observers of space, switched on in the run file's `[output]` table: hydrodynamic
//! modes (`modes.csv`), S(k) and g(r) (`structure.csv`), coarse-grained fields and particle
//! snapshots (VTK XML with `.pvd` time series for ParaView, LAMMPS dump and extended XYZ
//! trajectories: [`crate::snapshots`]), and maps of the fields as PNG
//! ([`crate::maps`]). They read the engine's
//! [`gas::system::System`] at the samples of the schedule, so every spatial engine has them;
//! the homogeneous DSMC schemes have no positions and refuse them. Field and snapshot files
//! are written during the run into the output directory ([`SpaceObserver::set_directory`]);
//! the CSV files and the collections at the end.

use crate::description::{OutputSection, RunDescription};
use crate::engines::Abilities;
use crate::error::{Error, Result};
use crate::maps;
use crate::observer::{record_of, records_from, Observer};
use crate::output::{number, write_csv_file};
use crate::plot::tick_label;
use crate::schedule::{Schedule, Target};
use crate::snapshots::{self, Snapshot};
use crate::validate::Plan;
use crate::vtk::{write_collection, write_fields, ParticleData};
use gas::structure::{
    coarse_grained_fields, hydrodynamic_modes, pair_correlation, structure_factor, Fields,
};
use gas::system::System;
use gas::theory::long_wavelength_structure_factor;
use gas::Engine;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::{Path, PathBuf};

/// Largest |n|² of the mode shells by default (|n|² = 1, 2, 3).
pub const MODE_SHELLS: usize = 3;
/// Largest grid per axis of `output.fields` in 1, 2, 3 dimensions.
const MAX_FIELD_GRID: [usize; 3] = [1 << 20, 4096, 256];
/// Most slabs of `output.profiles`.
const MAX_PROFILE_BINS: usize = 100_000;
/// Largest FFT grid per axis of S(k) in 1, 2, 3 dimensions.
const MAX_STRUCTURE_GRID: [usize; 3] = [1 << 20, 2048, 256];

/// The header of `modes.csv` (a contract).
pub const MODES_HEADER: [&str; 6] = [
    "time",
    "collisions_per_particle",
    "k",
    "transverse_energy",
    "longitudinal_energy",
    "density_power",
];
/// The header of `structure.csv`: `function` is `S` (x = k) or `g` (x = r).
pub const STRUCTURE_HEADER: [&str; 5] =
    ["time", "collisions_per_particle", "function", "x", "value"];

/// The message of a run asking for fields or snapshots without an output directory.
const NO_DIRECTORY: &str = "writes files during the run: give the run an output directory";

/// Checks `[output]` against what the engine can do (errors name the key and the allowed
/// range).
pub fn check_output(description: &RunDescription, engine: &Abilities) -> Result<()> {
    let Some(o) = &description.output else {
        return Ok(());
    };
    let spatial = engine.positions;
    let asked = [
        ("output.modes", o.modes),
        ("output.structure", o.structure),
        ("output.fields", o.fields.is_some()),
        ("output.snapshots", o.snapshots.is_some()),
        ("output.profiles", o.profiles.is_some()),
    ];
    for (key, on) in asked {
        if on && !spatial {
            return Err(Error::input(
                key,
                format!(
                    "needs positions: run.engine = {}",
                    crate::engines::kinds_that(|a| a.positions)
                ),
            ));
        }
    }
    // The shells of wave vectors (and g(r)'s pair counter) are those of a cube.
    for (key, on) in [("output.modes", o.modes), ("output.structure", o.structure)] {
        if on && !description.system.is_cubic() {
            return Err(Error::input(
                key,
                "needs a cubic box (its shells of wave vectors): give system.box equal sides \
                 or system.packing_fraction",
            ));
        }
    }
    if let Some(shells) = o.mode_shells {
        if !o.modes {
            return Err(Error::input(
                "output.mode_shells",
                "only with output.modes = true",
            ));
        }
        if !(1..=100).contains(&shells) {
            return Err(Error::out_of_range(
                "output.mode_shells",
                shells,
                "1 ..= 100",
            ));
        }
    }
    let dimension = description.system.dimension as usize;
    if let Some(f) = o.fields {
        let max = MAX_FIELD_GRID[dimension.clamp(1, 3) - 1];
        if !(3..=max).contains(&f.grid) {
            return Err(Error::out_of_range(
                "output.fields.grid",
                f.grid,
                &format!("3 ..= {max} cells per side in {dimension}D"),
            ));
        }
        every("output.fields.every", f.every)?;
    }
    if let Some(s) = &o.snapshots {
        every("output.snapshots.every", s.every)?;
        if cfg!(not(feature = "h5md")) && s.format.has(crate::description::SnapshotFormat::H5md) {
            return Err(Error::input(
                "output.snapshots.format",
                "`h5md`: this haff was built without H5MD support; build it with the cargo \
                 feature `h5md` (docs/particles.md)",
            ));
        }
    }
    if let Some(p) = o.profiles {
        if p.axis.index() >= dimension {
            return Err(Error::out_of_range(
                "output.profiles.axis",
                p.axis.name(),
                &crate::description::AXIS_NAMES[..dimension].join(" | "),
            ));
        }
        if !(1..=MAX_PROFILE_BINS).contains(&p.bins) {
            return Err(Error::out_of_range(
                "output.profiles.bins",
                p.bins,
                &format!("1 ..= {MAX_PROFILE_BINS}"),
            ));
        }
    }
    Ok(())
}

fn every(key: &str, k: usize) -> Result<()> {
    if (1..=1_000_000).contains(&k) {
        Ok(())
    } else {
        Err(Error::out_of_range(key, k, "1 ..= 1e6 samples"))
    }
}

/// `fields_NNNNNN.png`: the density and vorticity maps of a field sample ([`crate::maps`]),
/// the whole box in 2D, the mid-plane layer of cells at z = L/2 in 3D, nothing in 1D (nor
/// in a box of unequal sides: the maps are square); axes in units of the largest particle
/// diameter.
fn write_maps<const D: usize>(
    path: &Path,
    system: &gas::system::System<D>,
    fields: &Fields<D>,
    time: f64,
    cpp: f64,
) -> Result<()> {
    if !system.is_cubic() {
        return Ok(());
    }
    let mean_density = system.len() as f64 / system.volume();
    let Some((density, vorticity)) = maps::plane(fields, mean_density) else {
        return Ok(());
    };
    let diameter = 2.0 * system.radii.iter().copied().fold(0.0, f64::max);
    let (side, unit) = if diameter > 0.0 {
        (system.sides[0] / diameter, "sigma")
    } else {
        (system.sides[0], "L unit")
    };
    let what = if D == 3 {
        "mid-plane slice z = L/2"
    } else {
        "2D"
    };
    let title = format!(
        "{what}, N = {}: t = {}, {} collisions per particle",
        system.len(),
        tick_label(time),
        tick_label(cpp)
    );
    let maps = maps::density_and_vorticity(fields.grid, side, density, vorticity);
    maps::write_png(path, &title, unit, &maps)
}

/// The modes of one sample: (|n|², k, transverse, longitudinal, density) per shell.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModesSample {
    pub time: f64,
    pub collisions_per_particle: f64,
    pub shells: Vec<(usize, f64, f64, f64, f64)>,
}

/// S(k) and g(r) of one sample as (x, value) pairs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StructureSample {
    pub time: f64,
    pub collisions_per_particle: f64,
    pub structure_factor: Vec<(f64, f64)>,
    pub pair_correlation: Vec<(f64, f64)>,
}

/// The resolution of `structure.csv` for a state: the FFT grid of S(k) and the range and
/// bins of g(r). Public so that `haff bench observers` times exactly what a run computes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StructureResolution {
    /// FFT cells per side: one per largest diameter (k up to 2/sigma), rounded up to a
    /// power of two, within 8 ..= the dimension's maximum.
    pub grid: usize,
    /// g(r) up to 5 diameters (at most L/2).
    pub r_max: f64,
    /// g(r) bins of 0.05 diameter (10 ..= 2000).
    pub bins: usize,
}

/// The [`StructureResolution`] of `system` (a box of side L/100 stands in for the diameter
/// of point particles).
pub fn structure_resolution<const D: usize>(system: &System<D>) -> StructureResolution {
    let diameter = 2.0 * system.radii.iter().copied().fold(0.0, f64::max);
    let length = system.shortest_side();
    let diameter = if diameter > 0.0 {
        diameter
    } else {
        length / 100.0
    };
    let max = MAX_STRUCTURE_GRID[D - 1];
    let grid = ((length / diameter).ceil() as usize)
        .next_power_of_two()
        .clamp(8, max);
    let r_max = (5.0 * diameter).min(0.5 * length);
    let bins = ((r_max / (0.05 * diameter)).ceil() as usize).clamp(10, 2000);
    StructureResolution { grid, r_max, bins }
}

/// What the observers of space have recorded (kept in check-points).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceRecords {
    #[serde(default)]
    pub modes: Vec<ModesSample>,
    #[serde(default)]
    pub structure: Vec<StructureSample>,
    /// (time, file name) of the field files written.
    #[serde(default)]
    pub fields: Vec<(f64, String)>,
    /// (time, file name) of the snapshots written: the `.vtu`, or without `vtk` the
    /// trajectory holding the frame.
    #[serde(default)]
    pub snapshots: Vec<(f64, String)>,
    /// (file name, bytes) of each snapshot trajectory after its last frame
    /// ([`crate::snapshots`]); none without them, so that other runs' check-points keep
    /// their bytes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub trajectories: Vec<(String, u64)>,
}

/// The observers of `[output]` and their records.
#[derive(Debug, Clone)]
pub struct SpaceObserver {
    output: OutputSection,
    /// S(k → 0) of the homogeneous fluid at the run's packing fraction.
    structure_factor0: f64,
    /// The species' (diameter, mass), to label the particles of snapshots.
    species: Vec<(f64, f64)>,
    directory: Option<PathBuf>,
    /// Whether this process writes the files (rank 0 of a run on several ranks; the others
    /// keep the same records).
    writer: bool,
    pub records: SpaceRecords,
}

impl SpaceObserver {
    pub fn new(plan: &Plan) -> Self {
        let d = &plan.description;
        let phi = d.packing_fraction();
        // DSMC particles are points placed independently: their S(0) is that of an ideal
        // gas, whatever the packing fraction that sets their collision rate.
        let points = plan.engine.abilities().point_particles;
        let structure_factor0 = match (points, d.system.dimension) {
            (true, _) => 1.0,
            (false, 1) => long_wavelength_structure_factor::<1>(phi),
            (false, 2) => long_wavelength_structure_factor::<2>(phi),
            (false, _) => long_wavelength_structure_factor::<3>(phi),
        };
        let species = plan.species.iter().map(|s| (s.diameter, s.mass)).collect();
        SpaceObserver {
            output: d.output.clone().unwrap_or_default(),
            structure_factor0,
            species,
            directory: None,
            writer: true,
            records: SpaceRecords::default(),
        }
    }

    /// Whether this process writes the field and snapshot files (default true).
    pub fn set_writer(&mut self, writer: bool) {
        self.writer = writer;
    }

    /// Whether anything is asked for.
    pub fn is_on(&self) -> bool {
        let o = &self.output;
        o.modes || o.structure || o.fields.is_some() || o.snapshots.is_some()
    }

    /// Whether fields or snapshots are written during the run (they need a directory).
    pub fn writes_files(&self) -> bool {
        self.output.fields.is_some() || self.output.snapshots.is_some()
    }

    /// The directory field and snapshot files go to.
    pub fn set_directory(&mut self, dir: &Path) {
        self.directory = Some(dir.to_path_buf());
    }

    /// The directory field and snapshot files go to, if set.
    pub fn directory(&self) -> Option<&Path> {
        self.directory.as_deref()
    }

    /// Fails (naming the key) if fields or snapshots are asked for and no directory is set:
    /// checked before a run goes on, so that it never stops half-way through a sample.
    pub fn check_directory(&self) -> Result<()> {
        let key = if self.output.fields.is_some() {
            "output.fields"
        } else {
            "output.snapshots"
        };
        match &self.directory {
            None if self.writes_files() => Err(Error::input(key, NO_DIRECTORY)),
            _ => Ok(()),
        }
    }

    /// Checks the records of a check-point against the samples taken.
    pub fn check_records(&self, samples: usize) -> std::result::Result<(), String> {
        let o = &self.output;
        let due = |every: Option<usize>| every.map_or(0, |k| samples.div_ceil(k));
        let counts = [
            (
                "modes",
                self.records.modes.len(),
                if o.modes { samples } else { 0 },
            ),
            (
                "structure",
                self.records.structure.len(),
                if o.structure { samples } else { 0 },
            ),
            (
                "fields",
                self.records.fields.len(),
                due(o.fields.map(|f| f.every)),
            ),
            (
                "snapshots",
                self.records.snapshots.len(),
                due(o.snapshots.as_ref().map(|s| s.every)),
            ),
        ];
        for (name, have, want) in counts {
            if have != want {
                return Err(format!(
                    "{have} {name} records where {samples} samples ask for {want}"
                ));
            }
        }
        let formats = o.snapshots.as_ref().map(|s| s.format.list()).unwrap_or(&[]);
        for (name, _) in &self.records.trajectories {
            let asked = formats
                .iter()
                .any(|&f| snapshots::trajectory_name(f) == Some(name.as_str()));
            if !asked {
                return Err(format!(
                    "a trajectory `{name}` that output.snapshots does not ask for"
                ));
            }
        }
        Ok(())
    }

    /// Observes sample number `sample` (0-based) of `engine`.
    fn observe_sample<const D: usize>(
        &mut self,
        sample: usize,
        engine: &mut dyn Engine<D>,
    ) -> Result<()> {
        if !self.is_on() {
            return Ok(());
        }
        let (time, cpp) = (engine.time(), engine.collisions_per_particle());
        let energy_lost = engine.counters().energy_lost;
        let o = self.output.clone();
        let snapshot_due = o
            .snapshots
            .as_ref()
            .is_some_and(|s| sample.is_multiple_of(s.every));
        let fields_due = o.fields.is_some_and(|f| sample.is_multiple_of(f.every));
        if !(o.modes || o.structure || fields_due || snapshot_due) {
            return Ok(());
        }
        // what a snapshot needs of the engine besides the state, taken before the state: one
        // synchronization of the engine for all observers (2 ms at N = 1e5, 1 % of a
        // collision per particle; `haff bench observers`)
        let (collisions, baths, spins) = if snapshot_due {
            (
                engine
                    .collision_counts()
                    .map(|c| c.into_iter().map(u64::from).collect::<Vec<u64>>()),
                engine.bath_temperatures().map(<[f64]>::to_vec),
                engine.rotation().map(|r| r.angular.clone()),
            )
        } else {
            (None, None, None)
        };
        let system = engine.system();
        if o.modes {
            let shells = hydrodynamic_modes(
                system,
                o.mode_shells.unwrap_or(MODE_SHELLS),
                self.structure_factor0,
            )
            .iter()
            .map(|m| {
                (
                    m.norm2,
                    m.k,
                    m.transverse_energy,
                    m.longitudinal_energy,
                    m.density_power,
                )
            })
            .collect();
            self.records.modes.push(ModesSample {
                time,
                collisions_per_particle: cpp,
                shells,
            });
        }
        if o.structure {
            let StructureResolution { grid, r_max, bins } = structure_resolution(system);
            let pairs =
                |p: Vec<gas::structure::StructurePoint>| p.iter().map(|p| (p.x, p.value)).collect();
            self.records.structure.push(StructureSample {
                time,
                collisions_per_particle: cpp,
                structure_factor: pairs(structure_factor(system, grid)),
                pair_correlation: pairs(pair_correlation(system, r_max, bins)),
            });
        }
        if let (Some(f), true) = (o.fields, fields_due) {
            let name = format!("fields_{sample:06}.vti");
            let path = self.file(&name, "output.fields")?;
            if self.writer {
                let fields = coarse_grained_fields(system, f.grid);
                write_fields(&path, &fields)?;
                write_maps(&path.with_extension("png"), system, &fields, time, cpp)?;
            }
            self.records.fields.push((time, name));
        }
        if let (Some(s), true) = (&o.snapshots, snapshot_due) {
            let name = snapshots::record_name(&s.format, sample);
            let dir = self
                .directory
                .clone()
                .ok_or_else(|| Error::input("output.snapshots", NO_DIRECTORY))?;
            if self.writer {
                let species: Vec<u32> = system
                    .radii
                    .iter()
                    .zip(&system.masses)
                    .map(|(&r, &m)| self.species_of(2.0 * r, m))
                    .collect();
                let snapshot = Snapshot {
                    sample,
                    time,
                    system,
                    data: ParticleData {
                        collisions: collisions.as_deref(),
                        species: &species,
                        bath_temperatures: baths.as_deref(),
                        angular_velocities: spins.as_deref(),
                    },
                    energy_lost,
                };
                snapshots::write(&dir, &s.format, &snapshot, &mut self.records.trajectories)?;
            }
            self.records.snapshots.push((time, name));
        }
        Ok(())
    }

    /// The species whose (diameter, mass) is nearest.
    fn species_of(&self, diameter: f64, mass: f64) -> u32 {
        let distance = |&(d, m): &(f64, f64)| ((d - diameter) / d).abs() + ((m - mass) / m).abs();
        (0..self.species.len())
            .min_by(|&a, &b| distance(&self.species[a]).total_cmp(&distance(&self.species[b])))
            .unwrap_or(0) as u32
    }

    fn file(&self, name: &str, key: &str) -> Result<PathBuf> {
        match &self.directory {
            Some(dir) => Ok(dir.join(name)),
            None => Err(Error::input(key, NO_DIRECTORY)),
        }
    }

    /// Writes `modes.csv`, `structure.csv` and the `.pvd` collections into `dir`.
    fn write_files(&self, dir: &Path) -> Result<()> {
        let o = &self.output;
        if o.modes {
            let rows = self.records.modes.iter().flat_map(|s| {
                s.shells.iter().map(move |&(_, k, t, l, d)| {
                    [s.time, s.collisions_per_particle, k, t, l, d]
                        .map(number)
                        .to_vec()
                })
            });
            write_csv_file(&dir.join("modes.csv"), &MODES_HEADER, rows)?;
        }
        if o.structure {
            let rows = self.records.structure.iter().flat_map(|s| {
                let functions = [("S", &s.structure_factor), ("g", &s.pair_correlation)];
                functions.into_iter().flat_map(move |(name, points)| {
                    points.iter().map(move |&(x, v)| {
                        let time = [s.time, s.collisions_per_particle].map(number);
                        vec![
                            time[0].clone(),
                            time[1].clone(),
                            name.to_string(),
                            number(x),
                            number(v),
                        ]
                    })
                })
            });
            write_csv_file(&dir.join("structure.csv"), &STRUCTURE_HEADER, rows)?;
        }
        if o.fields.is_some() {
            write_collection(&dir.join("fields.pvd"), &self.records.fields)?;
        }
        let vtk = crate::description::SnapshotFormat::Vtk;
        if o.snapshots.as_ref().is_some_and(|s| s.format.has(vtk)) {
            write_collection(&dir.join("snapshots.pvd"), &self.records.snapshots)?;
        }
        Ok(())
    }
}

impl<const D: usize> Observer<D> for SpaceObserver {
    fn name(&self) -> &'static str {
        "space"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        match target.sample {
            Some(sample) => self.observe_sample(sample, engine),
            None => Ok(()),
        }
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(&self.records)
    }

    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        _engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let records: SpaceRecords = records_from(record)?;
        let previous = std::mem::replace(&mut self.records, records);
        if let Err(e) = self.check_records(schedule.samples_before(done)) {
            self.records = previous;
            return Err(e);
        }
        Ok(())
    }

    fn check_ready(&self) -> Result<()> {
        self.check_directory()
    }

    fn set_output(&mut self, dir: &Path, writer: bool) {
        self.set_directory(dir);
        self.set_writer(writer);
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_files(dir)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
