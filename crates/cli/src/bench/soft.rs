//! `haff bench soft-sphere`: time steps per second of soft-sphere MD of the gas of a run
//! file (the same file `bench/peers/lammps/gas_input.py` turns into a LAMMPS input, so the
//! two codes time the same gas).

use super::median_min_max;
use crate::error::{CliError, CliResult};
use crate::output::{parse_count, stdout, ReportFormat};
use gas::Engine;
use sim::validate::EngineSpec;
use std::io::Write;
use std::path::Path;

/// `haff bench soft-sphere [RUN_FILE]`: nanoseconds per time step per particle (one core),
/// the median of repeats after a warm-up of as many steps, with the engine's time step, the
/// neighbour-list rebuilds and the contacts begun. Without a file: 3D, N = 10^4,
/// phi = 0.05, Y = 1e5, nu = 0.3, A = 0.01, T = m = sigma = 1. A file with
/// `collision.friction` times rough spheres.
pub fn soft_sphere(args: &crate::BenchSoftArgs) -> CliResult {
    let text = match &args.run {
        Some(path) => std::fs::read_to_string(path)
            .map_err(|e| CliError::argument("RUN_FILE", format!("{}: {e}", path.display())))?,
        None => DEFAULT_GAS.to_string(),
    };
    let origin = args.run.clone().unwrap_or_else(|| "built-in gas".into());
    let description = sim::RunDescription::from_toml(&text, Path::new(&origin))
        .map_err(|e| CliError::argument("RUN_FILE", e))?;
    let mut description = description;
    description.run.engine = sim::description::EngineKind::SoftSphere;
    let plan = sim::validate(&description).map_err(|e| CliError::argument("RUN_FILE", e))?;
    let EngineSpec::SoftSphere(options, material) = plan.engine else {
        return Err(CliError::argument("RUN_FILE", "not a soft-sphere run"));
    };
    let s = &plan.description.system;
    if s.dimension != 3 || s.species.is_some() || s.sides.is_some() {
        return Err(CliError::argument(
            "RUN_FILE",
            "the benchmark takes one kind of sphere in 3D at system.packing_fraction",
        ));
    }
    let phi = plan.description.packing_fraction();
    let steps = parse_count("--steps", &args.steps, 1, 1_000_000_000)? as u64;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let (diameter, mass) = (plan.species[0].diameter, plan.species[0].mass);
    let mut per_particle_step = Vec::new();
    let (mut dt, mut builds, mut contacts) = (0.0, 0, 0);
    for repeat in 0..repeats {
        let system = gas::init::monodisperse::<3>(
            s.particles,
            phi,
            diameter,
            mass,
            s.temperature,
            s.seed + repeat as u64,
        )
        .map_err(|e| CliError::argument("RUN_FILE", e))?;
        let mut engine = sim::engines::soft_sphere(system.clone(), options, material)
            .map_err(|e| CliError::argument("RUN_FILE", e))?;
        // Rough spheres (collision.friction): their spins at the run's rotational
        // temperature.
        if let Some(rough) = &plan.rough {
            let spins = gas::rotation::Rotation::thermal(
                &system,
                vec![rough.inertia[0]; system.len()],
                rough.temperature,
                s.seed,
            );
            engine
                .set_friction(rough.friction)
                .and_then(|()| engine.set_rotation(Some(spins)))
                .map_err(|e| CliError::argument("RUN_FILE", e))?;
        }
        engine.run_steps(steps);
        let before = engine.counters().collisions;
        let start = std::time::Instant::now();
        engine.run_steps(steps);
        let seconds = start.elapsed().as_secs_f64();
        per_particle_step.push(seconds / (steps as f64 * s.particles as f64) * 1e9);
        dt = engine.time_step();
        builds = engine.neighbor_builds();
        contacts = engine.counters().collisions - before;
    }
    let [median, min, max] = median_min_max(per_particle_step);
    let report = serde_json::json!({
        "particles": s.particles,
        "packing_fraction": phi,
        "steps_per_repeat": steps,
        "repeats": repeats,
        "time_step": dt,
        "ns_per_particle_step": median,
        "ns_per_particle_step_min": min,
        "ns_per_particle_step_max": max,
        "neighbor_builds_last_repeat": builds,
        "contacts_begun_in_timed_steps": contacts,
    });
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => crate::output::write_json(&mut out, &report)?,
        ReportFormat::Table => writeln!(
            out,
            "N = {}, phi = {}, dt = {dt:.4e}: {median:.2} ns per particle per step (min {min:.2}, \
             max {max:.2}; median of {repeats} x {steps} steps), {contacts} contacts begun, \
             {builds} neighbour-list builds",
            s.particles, phi
        )?,
    }
    Ok(out.flush()?)
}

/// The gas timed without a run file.
const DEFAULT_GAS: &str = "[system]\ndimension = 3\nparticles = 10000\npacking_fraction = 0.05\n\
    seed = 1\n[collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\n\
    dissipative_constant = 0.01\n[run]\nengine = \"soft-sphere\"\nend_time = 1.0\n";
