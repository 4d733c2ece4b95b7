//! Granular-gas runs: `haff._haff._Simulation` wraps the library run driver
//! (`sim::Simulation`) that `haff run` drives, so that a run from Python and the same run
//! from the command line give the same numbers bit for bit. The run goes on with the GIL
//! released; between pieces of it (`sim::PIECE_COLLISIONS` collisions) the driver takes the
//! GIL back for a moment to call the progress callback and look for Ctrl-C.

use crate::{config_error, sim_error};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sim::observer::TIMESERIES_HEADER;
use sim::outdir::{run_hash, OutputDir, RunState};
use sim::space::{MODES_HEADER, STRUCTURE_HEADER};
use sim::species::SPECIES_HEADER;
use sim::{Point, Progress, Simulation};
use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySimulation>()?;
    Ok(())
}

/// The run driver's progress reports, passed on to a Python callable
/// `callback(done, total, note)`; Ctrl-C (or an exception in the callback) stops the run
/// at the next piece.
struct PyProgress {
    callback: Option<Py<PyAny>>,
    total: usize,
    /// The exception that stopped the run, raised when it has stopped.
    error: Option<PyErr>,
}

impl PyProgress {
    fn new(callback: Option<Py<PyAny>>) -> Self {
        PyProgress {
            callback,
            total: 0,
            error: None,
        }
    }

    /// Calls the callback and looks for signals, keeping the first exception.
    fn report(&mut self, done: usize, note: &str) {
        if self.error.is_some() {
            return;
        }
        Python::attach(|py| {
            let result = match &self.callback {
                Some(callback) => callback.call1(py, (done, self.total, note)).map(drop),
                None => Ok(()),
            };
            self.error = result.and_then(|()| py.check_signals()).err();
        });
    }

    /// The outcome of a run: its error, or the exception that stopped it.
    fn finish_run<T>(self, result: sim::Result<T>) -> PyResult<T> {
        match (self.error, result) {
            (Some(error), _) => Err(error),
            (None, result) => result.map_err(sim_error),
        }
    }
}

impl Progress for PyProgress {
    fn start(&mut self, total: usize, done: usize) {
        self.total = total;
        self.report(done, "");
    }
    fn sample(&mut self, done: usize, note: &str) {
        self.report(done, note);
    }
    fn keep_going(&mut self) -> bool {
        if self.error.is_none() {
            self.error = Python::attach(|py| py.check_signals().err());
        }
        self.error.is_none()
    }
}

/// A granular-gas run (the Python class `haff.Simulation` builds on it). The mutex makes
/// the class shareable between Python threads; PyO3's borrow checking already keeps one
/// caller at a time, so it is never contended.
#[pyclass(name = "_Simulation", module = "haff._haff")]
pub struct PySimulation {
    inner: Mutex<Simulation>,
}

impl PySimulation {
    fn new(simulation: Simulation) -> Self {
        PySimulation {
            inner: Mutex::new(simulation),
        }
    }

    /// The run, for a method that only reads it.
    fn get(&self) -> MutexGuard<'_, Simulation> {
        self.inner
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// The run, for a method that changes it.
    fn get_mut(&mut self) -> &mut Simulation {
        self.inner
            .get_mut()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

#[pymethods]
impl PySimulation {
    /// A run from TOML text; `origin` names it in error messages.
    #[staticmethod]
    fn from_toml(text: &str, origin: PathBuf) -> PyResult<Self> {
        let inner = Simulation::from_toml(text, &origin).map_err(sim_error)?;
        Ok(PySimulation::new(inner))
    }

    /// A run from TOML text whose particles are given as arrays (`system.initial`; see
    /// `particles::configuration`): checked as a particle file's, errors naming
    /// `initial.<array>` or the record.
    #[staticmethod]
    #[pyo3(signature = (text, origin, r#box, positions, velocities = None, diameters = None,
                        masses = None, species = None, spins = None))]
    #[allow(clippy::too_many_arguments)] // the configuration's arrays, each optional
    fn with_initial(
        py: Python<'_>,
        text: &str,
        origin: PathBuf,
        r#box: Vec<f64>,
        positions: numpy::PyReadonlyArray2<f64>,
        velocities: Option<numpy::PyReadonlyArray2<f64>>,
        diameters: Option<numpy::PyReadonlyArray1<f64>>,
        masses: Option<numpy::PyReadonlyArray1<f64>>,
        species: Option<Vec<usize>>,
        spins: Option<numpy::PyReadonlyArray2<f64>>,
    ) -> PyResult<Self> {
        let description = sim::RunDescription::from_toml(text, &origin).map_err(sim_error)?;
        let particles = crate::particles::configuration(
            r#box, positions, velocities, diameters, masses, species, spins, None,
        )?;
        let inner = py
            .detach(|| Simulation::with_initial(&description, particles))
            .map_err(sim_error)?;
        Ok(PySimulation::new(inner))
    }

    /// A run from a TOML file; errors name the file.
    #[staticmethod]
    fn from_path(path: PathBuf) -> PyResult<Self> {
        let in_file = |e: sim::Error| match e {
            sim::Error::Input { key, message } => {
                config_error(&format!("{}: {key}", path.display()), message)
            }
            other => sim_error(other),
        };
        let description = sim::RunDescription::from_path(&path).map_err(in_file)?;
        let inner = Simulation::new(&description).map_err(in_file)?;
        Ok(PySimulation::new(inner))
    }

    /// The run saved as the check-point `path` (a file, or a directory holding
    /// `checkpoint.bin`), verified and checked as `haff run --resume` does.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let inner = Simulation::load(&path).map_err(sim_error)?;
        Ok(PySimulation::new(inner))
    }

    /// Runs to the end (or until `stop_after` samples exist); GIL released.
    #[pyo3(signature = (callback=None, stop_after=None))]
    fn run(
        &mut self,
        py: Python<'_>,
        callback: Option<Py<PyAny>>,
        stop_after: Option<usize>,
    ) -> PyResult<bool> {
        let mut progress = PyProgress::new(callback);
        let inner = self.get_mut();
        let result = py.detach(|| inner.run(&mut progress, stop_after));
        progress.finish_run(result).map(|outcome| outcome.complete)
    }

    /// Runs to a time or a number of collisions per particle (exactly one); GIL released.
    #[pyo3(signature = (time=None, collisions_per_particle=None, callback=None))]
    fn advance(
        &mut self,
        py: Python<'_>,
        time: Option<f64>,
        collisions_per_particle: Option<f64>,
        callback: Option<Py<PyAny>>,
    ) -> PyResult<bool> {
        let point = match (time, collisions_per_particle) {
            (Some(t), None) => Point::Time(t),
            (None, Some(c)) => Point::CollisionsPerParticle(c),
            _ => {
                return Err(config_error(
                    "advance",
                    "give exactly one of time= and collisions_per_particle=",
                ))
            }
        };
        let mut progress = PyProgress::new(callback);
        let inner = self.get_mut();
        let result = py.detach(|| inner.advance(point, &mut progress));
        progress.finish_run(result)
    }

    /// The time series: column name -> values (the columns of `timeseries.csv`).
    fn timeseries<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let simulation = self.get();
        let samples = simulation.samples();
        let column =
            |f: fn(&sim::observer::Sample) -> f64| -> Vec<f64> { samples.iter().map(f).collect() };
        let floats: [(&str, Vec<f64>); 6] = [
            ("time", column(|s| s.time)),
            (
                "collisions_per_particle",
                column(|s| s.collisions_per_particle),
            ),
            ("temperature", column(|s| s.temperature)),
            ("a2", column(|s| s.a2)),
            ("energy_lost", column(|s| s.energy_lost)),
            ("pressure", column(|s| s.pressure)),
        ];
        let out = PyDict::new(py);
        for (name, values) in floats {
            debug_assert!(TIMESERIES_HEADER.contains(&name));
            out.set_item(name, PyArray1::from_vec(py, values))?;
        }
        let events: Vec<i64> = samples.iter().map(|s| s.events as i64).collect();
        out.set_item("events", PyArray1::from_vec(py, events))?;
        if samples.iter().any(|s| s.bath_temperature.is_some()) {
            let baths = column(|s| s.bath_temperature.unwrap_or(f64::NAN));
            out.set_item("bath_temperature", PyArray1::from_vec(py, baths))?;
        }
        if samples.iter().any(|s| s.rotational_temperature.is_some()) {
            let rotation = column(|s| s.rotational_temperature.unwrap_or(f64::NAN));
            out.set_item("rotational_temperature", PyArray1::from_vec(py, rotation))?;
        }
        Ok(out)
    }

    /// The per-species rows (the columns of `species.csv`; NaN where the collision
    /// frequency is not measured); None for a run without `system.species`.
    fn species_timeseries<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let simulation = self.get();
        let Some(rows) = simulation.species_samples() else {
            return Ok(None);
        };
        let column = |f: fn(&sim::species::SpeciesSample) -> f64| -> Vec<f64> {
            rows.iter().map(f).collect()
        };
        let out = PyDict::new(py);
        let floats: [(&str, Vec<f64>); 5] = [
            ("time", column(|s| s.time)),
            (
                "collisions_per_particle",
                column(|s| s.collisions_per_particle),
            ),
            ("temperature", column(|s| s.temperature)),
            ("a2", column(|s| s.a2)),
            (
                "collision_frequency",
                column(|s| s.collision_frequency.unwrap_or(f64::NAN)),
            ),
        ];
        for (name, values) in floats {
            debug_assert!(SPECIES_HEADER.contains(&name));
            out.set_item(name, PyArray1::from_vec(py, values))?;
        }
        let species: Vec<i64> = rows.iter().map(|s| s.species as i64).collect();
        out.set_item("species", PyArray1::from_vec(py, species))?;
        if rows.iter().any(|s| s.rotational_temperature.is_some()) {
            let rotation = column(|s| s.rotational_temperature.unwrap_or(f64::NAN));
            out.set_item("rotational_temperature", PyArray1::from_vec(py, rotation))?;
        }
        Ok(Some(out))
    }

    /// The walls' rows (the columns of `walls.csv`); None for a run in the periodic box.
    fn walls<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let simulation = self.get();
        let Some(rows) = simulation.wall_samples() else {
            return Ok(None);
        };
        let out = PyDict::new(py);
        let floats: [(&str, Vec<f64>); 4] = [
            ("time", rows.iter().map(|r| r.time).collect()),
            (
                "collisions_per_particle",
                rows.iter().map(|r| r.collisions_per_particle).collect(),
            ),
            ("momentum", rows.iter().map(|r| r.momentum).collect()),
            ("energy", rows.iter().map(|r| r.energy).collect()),
        ];
        for (name, values) in floats {
            debug_assert!(sim::walls::WALLS_HEADER.contains(&name));
            out.set_item(name, PyArray1::from_vec(py, values))?;
        }
        let axes: Vec<&str> = rows.iter().map(|r| r.axis.as_str()).collect();
        out.set_item("axis", axes)?;
        let sides: Vec<&str> = rows.iter().map(|r| r.side.name()).collect();
        out.set_item("side", sides)?;
        let collisions: Vec<i64> = rows.iter().map(|r| r.collisions as i64).collect();
        out.set_item("collisions", PyArray1::from_vec(py, collisions))?;
        Ok(Some(out))
    }

    /// The pressure tensor's rows (the columns of `pressure.csv`); None without
    /// `output.pressure` or `[shear]`.
    fn pressure<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let simulation = self.get();
        let Some(series) = simulation.pressure() else {
            return Ok(None);
        };
        let rows = &series.samples;
        let out = PyDict::new(py);
        let mut columns: Vec<(&str, Vec<f64>)> = vec![
            ("time", rows.iter().map(|r| r.time).collect()),
            (
                "collisions_per_particle",
                rows.iter().map(|r| r.collisions_per_particle).collect(),
            ),
        ];
        for (c, name) in ["pxx", "pyy", "pzz", "pxy", "pxz", "pyz"]
            .into_iter()
            .enumerate()
        {
            columns.push((name, rows.iter().map(|r| r.pressure[c]).collect()));
        }
        columns.push(("kinetic_xy", rows.iter().map(|r| r.kinetic_xy).collect()));
        for (name, values) in columns {
            debug_assert!(sim::rheology::PRESSURE_HEADER.contains(&name));
            out.set_item(name, PyArray1::from_vec(py, values))?;
        }
        Ok(Some(out))
    }

    /// `summary.json`'s `rheology` of the rows so far, as JSON text; None without `[shear]`.
    fn rheology(&self) -> PyResult<Option<String>> {
        let simulation = self.get();
        if simulation.plan().shear.is_none() {
            return Ok(None);
        }
        Ok(simulation
            .pressure()
            .map(|series| simulation.rheology(series).to_string()))
    }

    /// `summary.json`'s `green_kubo` of the rows so far, as JSON text; None without
    /// `output.pressure` or under `[shear]`.
    fn green_kubo(&self) -> PyResult<Option<String>> {
        let simulation = self.get();
        if simulation.plan().shear.is_some() {
            return Ok(None);
        }
        Ok(simulation
            .pressure()
            .map(|series| simulation.green_kubo(series).to_string()))
    }

    /// The profiles' rows (the columns of `profiles.csv`, NaN for its empty cells); None
    /// without `output.profiles`.
    fn profiles<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let simulation = self.get();
        let Some(rows) = simulation.profile_rows() else {
            return Ok(None);
        };
        let out = PyDict::new(py);
        let column = |f: &dyn Fn(&sim::profiles::ProfileRow) -> Option<f64>| -> Vec<f64> {
            rows.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect()
        };
        let mut columns: Vec<(String, Vec<f64>)> = vec![
            ("time".into(), column(&|r| Some(r.time))),
            (
                "collisions_per_particle".into(),
                column(&|r| Some(r.collisions_per_particle)),
            ),
            ("position".into(), column(&|r| Some(r.position))),
            ("density".into(), column(&|r| Some(r.density))),
            (
                "packing_fraction".into(),
                column(&|r| Some(r.packing_fraction)),
            ),
            ("temperature".into(), column(&|r| r.temperature)),
        ];
        for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
            columns.push((
                format!("temperature_{axis}"),
                column(&|r| r.temperature_component(k)),
            ));
        }
        for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
            columns.push((
                format!("velocity_{axis}"),
                column(&|r| r.velocity_component(k)),
            ));
        }
        // Rough particles: the rotation columns (a rough run's slabs are not all empty).
        if rows.iter().any(|r| r.angular_velocity.is_some()) {
            columns.push((
                "rotational_temperature".into(),
                column(&|r| r.rotational_temperature),
            ));
            for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
                columns.push((
                    format!("angular_velocity_{axis}"),
                    column(&|r| r.angular_velocity.as_ref().map(|w| w[k])),
                ));
            }
        }
        for (name, values) in columns {
            debug_assert!(
                sim::profiles::PROFILES_HEADER.contains(&name.as_str())
                    || sim::profiles::ROTATION_COLUMNS.contains(&name.as_str())
            );
            out.set_item(name, PyArray1::from_vec(py, values))?;
        }
        Ok(Some(out))
    }

    /// The velocity histograms taken at `run.histogram_at`: (target, time,
    /// collisions_per_particle, bin centres c, densities) each.
    #[allow(clippy::type_complexity)]
    fn velocity_histograms<'py>(
        &self,
        py: Python<'py>,
    ) -> Vec<(
        f64,
        f64,
        f64,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        self.get()
            .histograms()
            .iter()
            .map(|h| {
                let c = h.bins.iter().map(|b| b.0).collect();
                let density = h.bins.iter().map(|b| b.1).collect();
                (
                    h.target,
                    h.time,
                    h.collisions_per_particle,
                    PyArray1::from_vec(py, c),
                    PyArray1::from_vec(py, density),
                )
            })
            .collect()
    }

    /// The hydrodynamic modes recorded (`output.modes`): column name -> values, the
    /// columns and rows of `modes.csv` (one row per sample and shell).
    fn modes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let simulation = self.get();
        let rows: Vec<[f64; 6]> = simulation
            .space_records()
            .modes
            .iter()
            .flat_map(|s| {
                s.shells
                    .iter()
                    .map(move |&(_, k, t, l, d)| [s.time, s.collisions_per_particle, k, t, l, d])
            })
            .collect();
        let out = PyDict::new(py);
        for (i, name) in MODES_HEADER.into_iter().enumerate() {
            let values: Vec<f64> = rows.iter().map(|row| row[i]).collect();
            out.set_item(name, PyArray1::from_vec(py, values))?;
        }
        Ok(out)
    }

    /// S(k) and g(r) recorded (`output.structure`): the columns of `structure.csv`, rows in
    /// its order (per sample, S then g); `function` as a list of "S" and "g".
    #[allow(clippy::type_complexity)]
    fn structure<'py>(
        &self,
        py: Python<'py>,
    ) -> (
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        Vec<&'static str>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    ) {
        debug_assert_eq!(
            STRUCTURE_HEADER,
            ["time", "collisions_per_particle", "function", "x", "value"]
        );
        let simulation = self.get();
        let (mut time, mut cpp, mut function, mut x, mut value) =
            (vec![], vec![], vec![], vec![], vec![]);
        for s in &simulation.space_records().structure {
            for (name, points) in [("S", &s.structure_factor), ("g", &s.pair_correlation)] {
                for &(at, v) in points {
                    time.push(s.time);
                    cpp.push(s.collisions_per_particle);
                    function.push(name);
                    x.push(at);
                    value.push(v);
                }
            }
        }
        (
            PyArray1::from_vec(py, time),
            PyArray1::from_vec(py, cpp),
            function,
            PyArray1::from_vec(py, x),
            PyArray1::from_vec(py, value),
        )
    }

    /// (time, file name) of the field files written (`output.fields`).
    fn field_files(&self) -> Vec<(f64, String)> {
        self.get().space_records().fields.clone()
    }

    /// (time, file name) of the snapshot files written (`output.snapshots`).
    fn snapshot_files(&self) -> Vec<(f64, String)> {
        self.get().space_records().snapshots.clone()
    }

    /// The directory field and snapshot files are written to, if set.
    #[getter]
    fn output_dir(&self) -> Option<PathBuf> {
        self.get().output_dir().map(PathBuf::from)
    }

    /// Claims `dir` for this run, as `haff run --out DIR` does (new, empty, or holding
    /// this run's outputs; another run's only with `force`), and writes the field and
    /// snapshot files of `[output]` there during the run.
    fn set_output_dir(&mut self, dir: PathBuf, force: bool) -> PyResult<()> {
        let hash = run_hash(self.get().description());
        OutputDir::for_writing(&dir, "run", &hash, force).map_err(|e| match e {
            sim::Error::Input { message, .. } => config_error("output_dir", message),
            other => sim_error(other),
        })?;
        self.get_mut().set_output_dir(&dir);
        Ok(())
    }

    /// (positions, velocities, radii, masses) now: copies, (N, D), (N, D), (N,), (N,).
    #[allow(clippy::type_complexity)]
    fn particles<'py>(
        &mut self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        let p = self.get_mut().particles();
        let n = p.radii.len();
        let matrix = |values: Vec<f64>| PyArray1::from_vec(py, values).reshape([n, p.dimension]);
        Ok((
            matrix(p.positions)?,
            matrix(p.velocities)?,
            PyArray1::from_vec(py, p.radii),
            PyArray1::from_vec(py, p.masses),
        ))
    }

    /// The granular temperature now, T = <m c^2> / D.
    fn temperature(&mut self) -> f64 {
        self.get_mut().temperature()
    }

    #[getter]
    fn time(&self) -> f64 {
        self.get().time()
    }

    /// (collisions, events, energy_lost, tc_elastic_collisions) so far.
    fn counters(&self) -> (u64, u64, f64, u64) {
        let c = self.get().counters();
        (c.collisions, c.events, c.energy_lost, c.tc_elastic)
    }

    /// How a dense start was grown (`initial_state` of summary.json) as JSON, or None.
    fn initial_state_json(&self) -> Option<String> {
        self.get()
            .initial_state()
            .map(|s| serde_json::to_string(s).expect("plain numbers serialize"))
    }

    /// The contacts of a soft-sphere run (the keys of `contacts` in summary.json), or None.
    fn contact_statistics<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let report = self.get().report();
        let Some(contacts) = report.section("contacts") else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        for &(key, value) in &contacts.values {
            match value {
                gas::engine::ReportValue::Count(n) => d.set_item(key, n)?,
                gas::engine::ReportValue::Real(x) => d.set_item(key, x)?,
            }
        }
        Ok(Some(d))
    }

    #[getter]
    fn complete(&self) -> bool {
        self.get().is_complete()
    }

    #[getter]
    fn particle_count(&self) -> usize {
        self.get().description().system.particles
    }

    #[getter]
    fn dimension(&self) -> usize {
        self.get().description().system.dimension as usize
    }

    #[getter]
    fn wall_seconds(&self) -> f64 {
        self.get().wall_seconds()
    }

    /// The run description (normalized) as JSON.
    fn description_json(&self) -> PyResult<String> {
        serde_json::to_string(self.get().description())
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
    }

    /// Writes a check-point (a file, or `checkpoint.bin` in a directory).
    fn save(&mut self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let inner = self.get_mut();
        py.detach(|| inner.save(&path)).map_err(sim_error)
    }

    /// Writes the files `haff run --out DIR` writes (manifest, time series, histograms,
    /// figure, summary). A directory holding another run's outputs is refused unless
    /// `force`; one holding this run's (an earlier `write`) is updated.
    fn write(&mut self, py: Python<'_>, dir: PathBuf, force: bool) -> PyResult<()> {
        let hash = run_hash(self.get().description());
        let rename = |e: sim::Error| match e {
            sim::Error::Input { message, .. } => config_error("dir", message),
            other => sim_error(other),
        };
        let mut out = OutputDir::for_writing(&dir, "run", &hash, force).map_err(rename)?;
        let inner = self.get_mut();
        let path = dir.clone();
        py.detach(move || inner.write(&path)).map_err(sim_error)?;
        let inner = self.get();
        out.set_state(if inner.is_complete() {
            RunState::Complete
        } else {
            RunState::Stopped
        })
        .map_err(sim_error)
    }
}
