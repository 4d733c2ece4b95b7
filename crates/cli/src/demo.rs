//! `haff demo`: the main job of haff in seconds. A 3D gas cooling (against Haff's law, its
//! velocity distribution against the Maxwellian and the Sonine correction), a 2D gas
//! clustering, and eps(v) of ice spheres with every law side by side. The gases are run files
//! of [`sim::demo`] written beside their outputs, run as `haff run` runs them.

use crate::bench::log_spaced;
use crate::error::{CliError, CliResult};
use crate::output::{significant, stdout, write_table};
use crate::progress::Bar;
use crate::DemoArgs;
use restitution::material::ICE_BRIDGES_BETA_CGS;
use restitution::{Restitution, ScaledForm, Viscoelastic};
use sim::outdir::{run_hash, OutputDir, RunState};
use sim::{RunDescription, Simulation};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// The laws shown, one column each.
const LAWS: [&str; 7] = [
    "exact",
    "exact-naive",
    "fast",
    "pade:1/4",
    "pade:3/6",
    "series:10",
    "series:20",
];
/// beta of ice in (s/cm)^(1/5) (Bridges, Hatzes and Lin 1984, as quoted in MP2011).
const BETA: f64 = ICE_BRIDGES_BETA_CGS;
/// Impact speeds in cm/s: log-spaced, two per decade.
const SPEED_LOW: f64 = 0.01;
const SPEED_HIGH: f64 = 1000.0;
const SPEEDS: usize = 11;
/// Significant digits of the eps columns.
const EPS_DIGITS: usize = 6;

/// `haff demo`.
pub fn run(args: &DemoArgs) -> CliResult {
    if args.table {
        let mut out = stdout();
        eps_table(&mut out)?;
        return Ok(out.flush()?);
    }
    let dir = &args.out;
    std::fs::create_dir_all(dir).map_err(|e| CliError::argument("--out", e))?;
    let shown = |name: &str| dir.join(name).display().to_string();
    let mut out = stdout();
    writeln!(
        out,
        "haff demo: granular gases in a few seconds; everything is in {}/",
        dir.display()
    )?;

    let clock = Instant::now();
    let cooling = run_gas(dir, "cooling", sim::demo::COOLING)?;
    let report = sim::demo::cooling_report(&cooling)?;
    sim::demo::velocity_distribution_figure(
        &dir.join("velocity-distribution.png"),
        cooling.histograms(),
        &report,
    )?;
    let (a2, a2_error) = report.a2;
    writeln!(
        out,
        "\n1. A freely cooling gas: 3D, 4000 spheres, eps = 0.9, event-driven ({:.1} s)\n   \
         T / T_Haff = {:.3} after {} collisions per particle (Haff's law with the Enskog \
         rate and the cooling state's a2; no fit)\n   \
         Sonine a2 = {a2:.4} +- {a2_error:.4} in the cooling state; van Noije & Ernst: {:.4}\n   \
         {}  T(t) against Haff's law\n   \
         {}  the velocity distribution against the Maxwellian and Sonine\n   \
         {}  the run: timeseries.csv, velocity_histograms.csv, summary.json",
        clock.elapsed().as_secs_f64(),
        report.haff_ratio,
        report.collisions_per_particle,
        report.a2_theory,
        shown("cooling/temperature.png"),
        shown("velocity-distribution.png"),
        shown("cooling/"),
    )?;

    let clock = Instant::now();
    let mut clustering = run_gas(dir, "clustering", sim::demo::CLUSTERING)?;
    let cpp = clustering
        .samples()
        .last()
        .map_or(0.0, |s| s.collisions_per_particle);
    sim::demo::snapshot_figure(
        &dir.join("clustering.png"),
        &clustering.configuration(),
        &format!("20000 disks, eps = 0.7, after {cpp} collisions per particle"),
    )?;
    writeln!(
        out,
        "\n2. Clustering: 2D, 20000 disks, eps = 0.7, event-driven ({:.1} s)\n   \
         {}  the disks at the end: dense clusters and empty space\n   \
         {}  density and vorticity maps as the clusters grow\n   \
         {}  the same for ParaView (and fields.pvd)",
        clock.elapsed().as_secs_f64(),
        shown("clustering.png"),
        shown("clustering/fields_*.png"),
        shown("clustering/snapshots.pvd"),
    )?;

    writeln!(
        out,
        "\n3. One collision: the coefficient of restitution of ice spheres, every law"
    )?;
    eps_table(&mut out)?;
    writeln!(
        out,
        "\nNext: change {} and run it with `haff run {} --out my-cooling`; the guide is \
         docs/guide/ (start at docs/guide/first-run.md).",
        shown("cooling.toml"),
        shown("cooling.toml"),
    )?;
    Ok(out.flush()?)
}

/// Writes the run file `DIR/NAME.toml` and runs it into `DIR/NAME/` as `haff run` does
/// (replacing an earlier demo's run there).
fn run_gas(dir: &Path, name: &str, text: &str) -> CliResult<Simulation> {
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, text).map_err(|e| CliError::argument("--out", e))?;
    let description = RunDescription::from_toml(text, &file).map_err(CliError::in_file(&file))?;
    let mut simulation = Simulation::new(&description)?;
    let out = dir.join(name);
    let mut claimed =
        OutputDir::open(&out, None, "run", &run_hash(simulation.description()), true)?;
    simulation.set_output_dir(&out);
    simulation.run(&mut Bar::samples(), None)?;
    simulation.write(&out)?;
    claimed.set_state(RunState::Complete)?;
    Ok(simulation)
}

/// The eps(v) table of ice spheres for every law in [`LAWS`], with its title and note.
fn eps_table(out: &mut impl Write) -> CliResult {
    let laws = LAWS
        .iter()
        .map(|name| ice_law(name))
        .collect::<CliResult<Vec<_>>>()?;
    let header: Vec<String> = ["v [cm/s]", "v*"]
        .into_iter()
        .chain(LAWS)
        .map(String::from)
        .collect();
    let rows: Vec<Vec<String>> = log_spaced(SPEED_LOW, SPEED_HIGH, SPEEDS)
        .into_iter()
        .map(|v| table_row(v, &laws))
        .collect();
    writeln!(
        out,
        "eps(v) of ice spheres, beta = {BETA} (s/cm)^(1/5), v* = beta^(1/2) v^(1/10)"
    )?;
    write_table(out, &header, &rows)?;
    writeln!(
        out,
        "note: beta from Bridges et al. (1984) via MP2011; exact-naive ends the collision at \
         zero overlap, the others at zero force; series:K holds only for v* well below 1."
    )?;
    Ok(())
}

/// The law `name` for ice, in cm/s.
fn ice_law(name: &str) -> CliResult<Viscoelastic> {
    let form: ScaledForm = name.parse().map_err(|e| CliError::library("law", e))?;
    Viscoelastic::new(BETA, form).map_err(|e| CliError::library("beta", e))
}

/// v, v* and eps of every law at speed `v`.
fn table_row(v: f64, laws: &[Viscoelastic]) -> Vec<String> {
    let vstar = laws.first().map_or(f64::NAN, |law| law.vstar(v));
    [significant(v, 4), significant(vstar, 6)]
        .into_iter()
        .chain(laws.iter().map(|law| significant(law.eps(v), EPS_DIGITS)))
        .collect()
}
