//! `system.initial`: the particles of a file ([`crate::particles`]), of another run's last
//! check-point, or given in code (Python's arrays), read and checked before anything runs,
//! and the run description resolved from them. The resolved description (the plan's, kept
//! in check-points and `summary.json`) holds what the particles make: `system.particles`,
//! `system.box`, the species (each distinct diameter and mass, counted: `fraction` = the
//! count), the temperature of the velocities; a check-point is thus validated without the
//! file ([`Source::Saved`]).
//!
//! Refused with `initial`: `system.particles`, `packing_fraction` and `species` (the file
//! makes them), `box` when the file has one, `diameter` or `mass` when the file has the
//! column, `temperature` when it has velocities, a weight of DSMC particles other than 1.

use crate::description::{InitialSection, MomentumPolicy, RunDescription, SpeciesEntry};
use crate::error::{Error, Result};
use crate::particles::{Configuration, Format};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Where the particles of a run with `system.initial` come from.
pub(crate) enum Source {
    /// The file or run that `system.initial` names.
    Description,
    /// Particles given in code (`Simulation::with_initial`).
    Given(Configuration),
    /// A resolved description (a check-point's): nothing read.
    Saved,
}

/// The particles a run starts from, checked, with everything filled in: velocities (the
/// file's, or drawn at `system.temperature`), diameters, masses; and what a user is told of
/// them.
#[derive(Debug, Clone, PartialEq)]
pub struct Initial {
    pub configuration: Configuration,
    pub report: InitialReport,
}

/// Where a run's particles came from and what was done to them (`summary.json`:
/// `initial_particles`; kept in check-points).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialReport {
    /// The file (or check-point) read.
    pub source: String,
    /// The total momentum of the file's velocities, before any removal.
    pub momentum: Vec<f64>,
    pub momentum_removed: bool,
    /// Whether the velocities were drawn (the file has none).
    pub velocities_drawn: bool,
    /// Whether the file's spins were left out (smooth particles).
    pub spins_ignored: bool,
}

/// The description with `system.initial` resolved, and the particles (none for a
/// description without `initial` or a saved one).
pub(super) fn resolve(
    description: &RunDescription,
    source: Source,
    engine: &crate::engines::Abilities,
) -> Result<(RunDescription, Option<Arc<Initial>>)> {
    let s = &description.system;
    let Some(section) = &s.initial else {
        if let Source::Given(_) = source {
            return Err(Error::input(
                "system.initial",
                "particles given in code need `system.initial = {}` in the description",
            ));
        }
        return Ok((description.clone(), None));
    };
    if let Source::Saved = source {
        if s.particles == 0 || (s.sides.is_none() && s.packing_fraction.is_none()) {
            return Err(Error::input(
                "system.initial",
                "a saved description without the particles it resolved",
            ));
        }
        return Ok((description.clone(), None));
    }
    refuse_placement(description)?;
    let (mut configuration, origin, resolved_section) = load(description, section, source)?;
    fill_box(description, &mut configuration, &origin)?;
    configuration.check(&origin, engine.point_particles)?;
    let kinds = fill_kinds(description, &mut configuration)?;
    let had_velocities = configuration.velocities.is_some();
    if had_velocities && s.temperature_given {
        return Err(Error::input(
            "system.temperature",
            "the file gives the velocities; system.temperature sets those drawn for a file \
             without them: leave it out",
        ));
    }
    let momentum = fill_velocities(description, &mut configuration, section.momentum);
    let mut resolved = description.clone();
    let r = &mut resolved.system;
    r.particles = configuration.len();
    r.sides = Some(configuration.sides.clone());
    if !engine.walls {
        // An engine without space (homogeneous DSMC) knows the box by its volume alone:
        // the file's packing fraction, in a cube (`engines::initial`).
        let volume: f64 = configuration
            .diameters
            .as_ref()
            .expect("filled in")
            .iter()
            .map(|&d| ball_volume(configuration.dimension, d))
            .sum();
        r.packing_fraction = Some(volume / configuration.sides.iter().product::<f64>());
        r.sides = None;
    }
    if had_velocities {
        r.temperature = temperature(&configuration);
        if r.temperature == 0.0 {
            return Err(Error::input(
                "system.initial",
                format!(
                    "the velocities of {} are all zero: a gas at rest has no temperature to                      scale the run by (leave the velocity columns out to draw them at                      system.temperature)",
                    origin.display()
                ),
            ));
        }
    }
    match kinds.as_slice() {
        [(diameter, mass, _)] => {
            r.diameter = Some(*diameter);
            r.mass = Some(*mass);
            r.species = None;
        }
        _ => {
            r.diameter = None;
            r.mass = None;
            r.species = Some(
                kinds
                    .iter()
                    .map(|&(diameter, mass, count)| SpeciesEntry {
                        diameter,
                        mass,
                        fraction: count as f64,
                        young: None,
                        poisson: None,
                        dissipative_constant: None,
                        inertia: None,
                    })
                    .collect(),
            );
        }
    }
    r.initial = Some(resolved_section);
    let report = InitialReport {
        source: origin.display().to_string(),
        momentum,
        momentum_removed: had_velocities && section.momentum == Some(MomentumPolicy::Remove),
        velocities_drawn: !had_velocities,
        spins_ignored: false,
    };
    let initial = Initial {
        configuration,
        report,
    };
    Ok((resolved, Some(Arc::new(initial))))
}

/// The keys a file's particles replace.
fn refuse_placement(description: &RunDescription) -> Result<()> {
    let s = &description.system;
    let why = "the particles come from system.initial";
    if s.particles != 0 {
        return Err(Error::input(
            "system.particles",
            format!("{why} (their number too): leave it out"),
        ));
    }
    if s.packing_fraction.is_some() {
        return Err(Error::input(
            "system.packing_fraction",
            format!("{why} (with their box): leave it out"),
        ));
    }
    if s.species.is_some() {
        return Err(Error::input(
            "system.species",
            format!(
                "{why}: their diameters and masses make the species (give system.diameter, \
                 system.mass or system.initial.density for a file without those columns)"
            ),
        ));
    }
    if description.run.particle_weight.is_some_and(|w| w != 1.0) {
        return Err(Error::input(
            "run.particle_weight",
            format!("{why}: each is one particle (leave out the weight)"),
        ));
    }
    Ok(())
}

/// The configuration `section` names (or that given), the path to name in messages, and
/// the section in its normal form (the file's absolute path, its format, the frame).
fn load(
    description: &RunDescription,
    section: &InitialSection,
    source: Source,
) -> Result<(Configuration, PathBuf, InitialSection)> {
    let dimension = description.system.dimension as usize;
    let mut normal = section.clone();
    normal.momentum.get_or_insert(MomentumPolicy::Keep);
    if let Some(density) = section.density {
        if !(density.is_finite() && (1e-30..=1e30).contains(&density)) {
            return Err(Error::out_of_range(
                "system.initial.density",
                crate::output::number(density),
                "1e-30 <= density <= 1e30",
            ));
        }
    }
    match (&section.file, &section.run, source) {
        (None, None, Source::Given(configuration)) => {
            Ok((configuration, PathBuf::from("<given particles>"), normal))
        }
        (Some(_), _, Source::Given(_)) | (_, Some(_), Source::Given(_)) => Err(Error::input(
            "system.initial",
            "particles given in code and a file or run in system.initial: give one",
        )),
        (Some(_), Some(_), _) => Err(Error::input(
            "system.initial.run",
            "give either system.initial.file or system.initial.run, not both",
        )),
        (None, None, _) => Err(Error::input(
            "system.initial",
            "give system.initial.file (a particle file) or system.initial.run (a run's \
             output directory)",
        )),
        (Some(file), None, _) => {
            let format = match &section.format {
                Some(name) => Format::parse("system.initial.format", name)?,
                None => Format::of_extension(Path::new(file)).ok_or_else(|| {
                    Error::input(
                        "system.initial.format",
                        format!(
                            "missing, and the extension of `{file}` names no format; \
                             allowed: {}",
                            Format::NAMES.join(", ")
                        ),
                    )
                })?,
            };
            let frame = section.frame.unwrap_or(-1);
            let path = absolute(Path::new(file));
            let configuration = crate::particles::read_unboxed(&path, format, dimension, frame)?;
            normal.file = Some(path.display().to_string());
            normal.format = Some(format.name().to_string());
            normal.frame = Some(frame);
            Ok((configuration, path, normal))
        }
        (None, Some(run), _) => {
            for (key, given) in [
                ("system.initial.format", section.format.is_some()),
                ("system.initial.frame", section.frame.is_some()),
            ] {
                if given {
                    return Err(Error::input(
                        key,
                        "for a particle file (system.initial.file); a run continues from its \
                         last check-point or snapshot",
                    ));
                }
            }
            let dir = absolute(Path::new(run));
            let (configuration, read) = last_state(&dir, dimension)?;
            normal.run = Some(dir.display().to_string());
            Ok((configuration, read, normal))
        }
    }
}

/// `path` made absolute against the working directory (the normal form names files
/// wherever the run is resumed).
fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

/// The particles of the last state the run in `dir` kept: its check-point
/// (`checkpoint.bin`, checked as a resumed run's), else its last snapshot (`output.snapshots`
/// in any format: `snapshots.h5md`, the last `snapshot_NNNNNN.vtu`, `snapshots.xyz`,
/// `snapshots.lammpstrj`), and the file read.
fn last_state(dir: &Path, dimension: usize) -> Result<(Configuration, PathBuf)> {
    let checkpoint = dir.join(crate::checkpoint::FILE_NAME);
    if !checkpoint.exists() {
        return last_snapshot(dir, dimension);
    }
    let mut run = crate::Simulation::load(dir).map_err(|e| {
        Error::input(
            "system.initial.run",
            format!(
                "{}: the run's check-point cannot be read: {e}",
                dir.display()
            ),
        )
    })?;
    let theirs = run.description().system.dimension as usize;
    if theirs != dimension {
        return Err(Error::input(
            "system.dimension",
            format!(
                "{dimension}, but the run in {} is in {theirs} dimensions: give \
                 system.dimension = {theirs}",
                dir.display()
            ),
        ));
    }
    Ok((run.configuration(), checkpoint))
}

/// The last snapshot of the run in `dir`, for a run that kept no check-point.
fn last_snapshot(dir: &Path, dimension: usize) -> Result<(Configuration, PathBuf)> {
    let last_vtu = std::fs::read_dir(dir).ok().and_then(|entries| {
        entries
            .filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().into_owned()))
            .filter(|n| n.starts_with("snapshot_") && n.ends_with(".vtu"))
            .max()
    });
    let candidates = [
        Some(("snapshots.h5md".to_string(), Format::H5md)),
        last_vtu.map(|n| (n, Format::Vtk)),
        Some(("snapshots.xyz".to_string(), Format::Xyz)),
        Some(("snapshots.lammpstrj".to_string(), Format::LammpsDump)),
    ];
    for (name, format) in candidates.into_iter().flatten() {
        let path = dir.join(name);
        if path.exists() {
            let c = crate::particles::read(&path, format, dimension, -1)?;
            return Ok((c, path));
        }
    }
    Err(Error::input(
        "system.initial.run",
        format!(
            "{}: no check-point (checkpoint.bin: haff run --checkpoint-every K) and no \
             snapshots (output.snapshots) to continue from",
            dir.display()
        ),
    ))
}

/// The box: the file's, or `system.box` for a file without one (refused with one).
fn fill_box(description: &RunDescription, c: &mut Configuration, origin: &Path) -> Result<()> {
    let given = &description.system.sides;
    match (c.sides.is_empty(), given) {
        (false, Some(_)) => Err(Error::input(
            "system.box",
            format!("{} gives the box: leave out system.box", origin.display()),
        )),
        (true, None) => Err(Error::input(
            "system.box",
            format!("missing: {} gives no box", origin.display()),
        )),
        (true, Some(sides)) => {
            c.sides = sides.clone();
            Ok(())
        }
        (false, None) => Ok(()),
    }
}

/// Fills in each particle's diameter and mass (the file's columns, else `system.diameter`,
/// `system.initial.density` or `system.mass`) and returns the kinds of particle, each
/// distinct (diameter, mass) with its count, ordered by the file's species label, then by
/// first appearance.
fn fill_kinds(
    description: &RunDescription,
    c: &mut Configuration,
) -> Result<Vec<(f64, f64, usize)>> {
    let s = &description.system;
    let density = s.initial.as_ref().and_then(|i| i.density);
    let n = c.len();
    if c.diameters.is_some() && s.diameter.is_some() {
        return Err(Error::input(
            "system.diameter",
            "the file gives the diameters: leave it out",
        ));
    }
    if c.masses.is_some() {
        for (key, given) in [
            ("system.mass", s.mass.is_some()),
            ("system.initial.density", density.is_some()),
        ] {
            if given {
                return Err(Error::input(key, "the file gives the masses: leave it out"));
            }
        }
    } else if s.mass.is_some() && density.is_some() {
        return Err(Error::input(
            "system.initial.density",
            "give either system.mass or system.initial.density, not both",
        ));
    }
    if let Some(d) = s.diameter {
        super::in_scale("system.diameter", d)?;
    }
    if let Some(m) = s.mass {
        super::in_scale("system.mass", m)?;
    }
    let diameters = c
        .diameters
        .take()
        .unwrap_or_else(|| vec![s.diameter.unwrap_or(1.0); n]);
    let dimension = s.dimension as usize;
    let masses = match (c.masses.take(), density) {
        (Some(m), _) => m,
        (None, Some(rho)) => diameters
            .iter()
            .map(|&d| rho * ball_volume(dimension, d))
            .collect(),
        (None, None) => {
            let labels = c.species.as_ref().map_or(1, |l| distinct(l));
            let sizes = distinct(&diameters.iter().map(|d| d.to_bits()).collect::<Vec<_>>());
            if s.mass.is_none() && (sizes > 1 || labels > 1) {
                return Err(Error::input(
                    "system.initial",
                    "the file has particles of several kinds (species or diameters) and no \
                     masses: give system.initial.density (m = density x volume) or \
                     system.mass (all alike)",
                ));
            }
            vec![s.mass.unwrap_or(1.0); n]
        }
    };
    if let Some(i) = masses
        .iter()
        .chain(&diameters)
        .position(|x| !(1e-30..=1e30).contains(x))
    {
        let (what, value) = if i < n {
            ("mass", masses[i])
        } else {
            ("diameter", diameters[i - n])
        };
        return Err(Error::out_of_range(
            "system.initial",
            format!("a particle's {what} {value}"),
            "1e-30 <= value <= 1e30",
        ));
    }
    let labels = c.species.clone().unwrap_or_else(|| vec![0; n]);
    let mut kinds: Vec<(usize, f64, f64, usize)> = Vec::new();
    for i in 0..n {
        let key = (labels[i], diameters[i], masses[i]);
        // Particles are told apart by diameter and mass: labels only order the kinds.
        if let Some(kind) = kinds.iter_mut().find(|k| (k.1, k.2) == (key.1, key.2)) {
            kind.3 += 1;
            continue;
        }
        if kinds.len() == gas::dsmc::MAX_SPECIES {
            return Err(Error::input(
                "system.initial",
                format!(
                    "the file has more than {0} kinds of particle (distinct diameter and \
                     mass); allowed: at most {0}",
                    gas::dsmc::MAX_SPECIES
                ),
            ));
        }
        kinds.push((key.0, key.1, key.2, 1));
    }
    kinds.sort_by_key(|k| k.0);
    c.diameters = Some(diameters);
    c.masses = Some(masses);
    Ok(kinds.into_iter().map(|(_, d, m, n)| (d, m, n)).collect())
}

/// The volume of a ball of diameter `d` in `dimension` dimensions (a disk's area, a rod's
/// length).
fn ball_volume(dimension: usize, d: f64) -> f64 {
    match dimension {
        1 => d,
        2 => std::f64::consts::PI * d * d / 4.0,
        _ => std::f64::consts::PI * d * d * d / 6.0,
    }
}

/// The number of distinct values in `list`.
fn distinct<T: Ord + Copy>(list: &[T]) -> usize {
    let mut set: Vec<T> = list.to_vec();
    set.sort_unstable();
    set.dedup();
    set.len()
}

/// Fills in velocities drawn at `system.temperature` for a file without them, or removes
/// the file's total momentum if `momentum = "remove"`; returns the file's total momentum
/// (zero for drawn velocities).
fn fill_velocities(
    description: &RunDescription,
    c: &mut Configuration,
    policy: Option<MomentumPolicy>,
) -> Vec<f64> {
    let s = &description.system;
    let d = c.dimension;
    let masses = c.masses.clone().expect("filled in by fill_kinds");
    let Some(velocities) = &mut c.velocities else {
        let drawn: Vec<[f64; 3]> = match d {
            1 => lift(gas::init::thermal_velocities::<1>(
                &masses,
                s.temperature,
                s.seed,
            )),
            2 => lift(gas::init::thermal_velocities::<2>(
                &masses,
                s.temperature,
                s.seed,
            )),
            _ => lift(gas::init::thermal_velocities::<3>(
                &masses,
                s.temperature,
                s.seed,
            )),
        };
        c.velocities = Some(drawn);
        return vec![0.0; d];
    };
    let momentum: Vec<f64> = (0..d)
        .map(|k| velocities.iter().zip(&masses).map(|(v, m)| m * v[k]).sum())
        .collect();
    if policy == Some(MomentumPolicy::Remove) {
        let total: f64 = masses.iter().sum();
        for v in velocities.iter_mut() {
            for k in 0..d {
                v[k] -= momentum[k] / total;
            }
        }
    }
    momentum
}

/// Vectors of D components as the configuration's three.
fn lift<const D: usize>(list: Vec<[f64; D]>) -> Vec<[f64; 3]> {
    list.into_iter()
        .map(|v| std::array::from_fn(|k| if k < D { v[k] } else { 0.0 }))
        .collect()
}

/// The temperature of the configuration's velocities, sum m v^2 / (N D).
fn temperature(c: &Configuration) -> f64 {
    let (v, m) = (c.velocities.as_ref(), c.masses.as_ref());
    let (Some(v), Some(m)) = (v, m) else {
        return f64::NAN;
    };
    let d = c.dimension;
    let sum: f64 = v
        .iter()
        .zip(m)
        .map(|(v, m)| m * v[..d].iter().map(|x| x * x).sum::<f64>())
        .sum();
    sum / (c.len() * d) as f64
}

/// What the plan of a run with `system.initial` still needs once the rest is checked: the
/// file's spins for rough particles (their rotational temperature resolved in the
/// description, the bound of their energy) or noted as left out for smooth ones, and the
/// notes a user reads before the run (where the particles come from, their momentum).
pub(super) fn finish(plan: &mut super::Plan) -> Result<()> {
    let Some(initial) = plan.initial.as_mut() else {
        return Ok(());
    };
    let c = &initial.configuration;
    let d = c.dimension;
    if let Some(spins) = &c.spins {
        match plan.rough.as_mut() {
            Some(rough) => {
                if plan.description.system.rotational_temperature.is_some() {
                    return Err(Error::input(
                        "system.rotational_temperature",
                        "the file gives the spins: leave it out",
                    ));
                }
                let kinds: Vec<(f64, f64)> =
                    plan.species.iter().map(|x| (x.diameter, x.mass)).collect();
                let diameters = c.diameters.as_ref().expect("filled in");
                let masses = c.masses.as_ref().expect("filled in");
                let mut sum = 0.0;
                for (i, w) in spins.iter().enumerate() {
                    let kind = kinds
                        .iter()
                        .position(|&k| k == (diameters[i], masses[i]))
                        .expect("the species are the file's kinds");
                    let moment = rough.inertia[kind] * masses[i] * 0.25 * diameters[i].powi(2);
                    let w2 = if d == 2 {
                        w[2] * w[2]
                    } else {
                        w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
                    };
                    sum += moment * w2;
                }
                let freedoms = (c.len() * gas::rotation::rotational_dimension(d)) as f64;
                let t = sum / freedoms;
                if t > 0.0 {
                    rough.temperature = t;
                    plan.description.system.rotational_temperature = Some(t);
                }
            }
            None => std::sync::Arc::make_mut(initial).report.spins_ignored = true,
        }
    }
    let initial = plan.initial.as_ref().expect("checked above");
    let (count, initial) = (initial.configuration.len(), &initial.report);
    let mut note = format!("system.initial: {count} particles from {}", initial.source);
    if initial.velocities_drawn {
        note += ", velocities drawn at system.temperature";
    } else {
        let p: Vec<String> = initial
            .momentum
            .iter()
            .map(|&x| crate::output::number(x))
            .collect();
        note += &format!(
            ", total momentum ({}) {}",
            p.join(", "),
            match initial.momentum_removed {
                true => "removed (momentum = \"remove\")",
                false => "kept (momentum = \"remove\" subtracts it)",
            }
        );
    }
    if initial.spins_ignored {
        note += "; the file's spins left out (smooth particles)";
    }
    plan.notes.push(note);
    Ok(())
}
