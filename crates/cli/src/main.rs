//! `haff`: granular-gas physics from the command line.
//!
//! This file holds the command-line grammar (clap) and the dispatch to the commands; the
//! commands themselves parse and validate their arguments, call the `restitution` library
//! and write the output. Every failure is one line `haff: error: <message>` on stderr and
//! a non-zero exit code (2 for bad input).

mod algebra;
mod bench;
mod cor;
mod demo;
mod error;
mod output;
mod progress;
mod reproduce;
mod rods;
mod run;
mod schema;
mod study;

use clap::error::ErrorKind;
use clap::{Args, Parser, Subcommand};
use error::{CliError, CliResult};
use output::{DataFormat, ReportFormat};
use std::process::ExitCode;

/// Granular-gas physics from the command line.
#[derive(Debug, Parser)]
#[command(name = "haff", version, arg_required_else_help = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// The coefficient of restitution: laws, single collisions, the linear dash-pot.
    #[command(subcommand)]
    Cor(CorCommand),
    /// Timing measurements.
    #[command(subcommand)]
    Bench(BenchCommand),
    /// The main job in seconds: a cooling gas against Haff's law and the Maxwellian, a 2D
    /// gas clustering, eps(v) of ice for every law; figures and run files in demo/.
    Demo(DemoArgs),
    /// A granular-gas run described by a TOML run file (event-driven MD, DSMC, soft-sphere).
    Run(RunArgs),
    /// A study: the runs of a run file over a grid of parameters and seeds, with their
    /// means and standard errors (ensemble.csv, study.json, figures/).
    Study(StudyArgs),
    /// Giese's vibrating rods: the collision equation, p(eps^2), the rod-chain MD.
    #[command(subcommand)]
    Rods(RodsCommand),
    /// The figures and tables of the papers, recomputed: CSV, PNG, SVG and a note per ID.
    Reproduce(ReproduceArgs),
    /// The JSON Schema of the run file (for editors: completion, hover docs, errors as
    /// you type; docs/guide/editors.md), or with --reference its keys as Markdown.
    Schema(SchemaArgs),
}

/// Arguments of `haff schema`.
#[derive(Debug, Args)]
pub struct SchemaArgs {
    /// Print the Markdown reference of every key (docs/guide/reference.md) instead of the
    /// schema.
    #[arg(long)]
    pub reference: bool,
}

/// Arguments of `haff reproduce`.
#[derive(Debug, Args)]
pub struct ReproduceArgs {
    /// The item to reproduce (see --list), or `all`.
    #[arg(required_unless_present = "list")]
    pub id: Option<String>,
    /// Output directory: ID.csv, ID.png, ID.svg, ID.md per item.
    #[arg(long, default_value = "reproduce")]
    pub out: std::path::PathBuf,
    /// Fewer points, lower orders and fewer seeds: most items take seconds, `all` a few
    /// minutes (213 s on a shared 2-core machine; kinetic-a2 the longest, 73 s).
    #[arg(long)]
    pub quick: bool,
    /// One line per ID: paper, figure or table, typical time, what it shows.
    #[arg(long, conflicts_with = "id")]
    pub list: bool,
    /// Also write a Markdown gallery of the items run (their figures, results and
    /// differences from the papers) to this file, its links relative to it
    /// (`haff reproduce all --out docs/reproduction --gallery docs/reproduction.md`).
    #[arg(long)]
    pub gallery: Option<std::path::PathBuf>,
}

#[derive(Debug, Subcommand)]
enum RodsCommand {
    /// eps of two cold rods (T_bath = 0) solved from Eq. (3) of Giese, closed forms beside it.
    Deterministic(RodsDeterministicArgs),
    /// eps from realizations of the stochastic Eq. (3): samples or the histogram of eps^2.
    Collide(RodsCollideArgs),
    /// Quantiles of eps^2 on a grid of E_tr/T_bath, as JSON for the tabulated law.
    Table(RodsTableArgs),
    /// Two cold rods colliding on a ring (Figs. 1 and 2 of Giese): energy, entropy, spectrum.
    TwoRods(RodsTwoRodsArgs),
    /// Rod-chain MD of Eq. (2) from a TOML file, optionally against ED + Monte Carlo.
    // The flags are `haff run`'s; the file and what --check does are the chain's own.
    #[command(
        mut_arg("file", |a| a.help(
            "The chain file ([chain] and [run]; every key: docs/guide/rods.md); not with --resume"
        )),
        mut_arg("check", |a| a.help(
            "Check the chain file as the run would before its first step (keys, ranges, the \
             ring, the table of \"tabulated\") and print it as TOML, every default filled in; \
             nothing runs, nothing is written. Exit 0 or 2"
        ))
    )]
    Chain(RunArgs),
}

/// Arguments of `haff rods two-rods`.
#[derive(Debug, Args)]
pub struct RodsTwoRodsArgs {
    /// Length ratio gamma = l1/l2.
    #[arg(long, default_value = "0.6173", allow_hyphen_values = true)]
    pub gamma: String,
    /// kappa = alpha l V0 / c.
    #[arg(long, default_value = "4000", allow_hyphen_values = true)]
    pub kappa: String,
    /// Modes per rod; a comma-separated list runs one experiment per value.
    #[arg(long, default_value = "75", allow_hyphen_values = true)]
    pub modes: String,
    /// Collisions per experiment.
    #[arg(long, default_value = "4500", allow_hyphen_values = true)]
    pub collisions: String,
    /// Collisions before the averages (spectrum, plateau) start.
    #[arg(long, default_value = "500", allow_hyphen_values = true)]
    pub transient: String,
    /// Step constant c_h of the contact integrator (energy drift ~1e-10 at 0.125).
    #[arg(long, default_value = "0.125", allow_hyphen_values = true)]
    pub step: String,
    /// Output directory: two_rods.csv, spectrum.csv, summary.json, energy.png, entropy.png,
    /// spectrum.png.
    #[arg(long)]
    pub out: std::path::PathBuf,
}

/// Arguments of `haff rods deterministic`.
#[derive(Debug, Args)]
pub struct RodsDeterministicArgs {
    /// Length ratio(s) gamma = l1/l2, comma-separated, 1e-3 <= gamma <= 1e3 (the work grows as
    /// kappa and as 1/gamma^2 away from 1: a call estimated beyond about a minute is refused).
    #[arg(long, allow_hyphen_values = true)]
    pub gamma: String,
    /// Scaled impact speed(s) kappa = alpha l V / c, comma-separated, 1 <= kappa <= 1e5.
    #[arg(long, allow_hyphen_values = true)]
    pub kappa: String,
    /// Integration step times kappa, 0 < h kappa < 1 (converged to ~4e-7 at 0.02).
    #[arg(long, default_value = "0.02", allow_hyphen_values = true)]
    pub step: String,
}

/// Arguments of `haff rods collide`.
#[derive(Debug, Args)]
pub struct RodsCollideArgs {
    /// Length ratio gamma = l1/l2, 1e-3 <= gamma <= 1e3.
    #[arg(long, allow_hyphen_values = true)]
    pub gamma: String,
    /// Scaled impact speed kappa = alpha l V / c, 1 <= kappa <= 1e5.
    #[arg(long, allow_hyphen_values = true)]
    pub kappa: String,
    /// E_tr / T_bath, 1e-4 ..= 1e6, or inf (cold bath, the deterministic eps) [default: inf].
    #[arg(long, allow_hyphen_values = true)]
    pub bath_ratio: Option<String>,
    /// Number of noise realizations.
    #[arg(long, default_value = "8000", allow_hyphen_values = true)]
    pub realizations: String,
    /// Seed (the samples do not depend on the number of threads).
    #[arg(long, default_value = "1", allow_hyphen_values = true)]
    pub seed: String,
    /// Print the histogram of eps^2 with this many bins on [0, --max) instead of the samples.
    #[arg(long, allow_hyphen_values = true)]
    pub histogram: Option<String>,
    /// Upper end of the histogram of eps^2.
    #[arg(long, default_value = "4", allow_hyphen_values = true)]
    pub max: String,
    /// With --histogram: also draw the density and the distribution function as a PNG.
    #[arg(long, requires = "histogram")]
    pub plot: Option<std::path::PathBuf>,
}

/// Arguments of `haff rods table`.
#[derive(Debug, Args)]
pub struct RodsTableArgs {
    /// Length ratio gamma = l1/l2.
    #[arg(long, allow_hyphen_values = true)]
    pub gamma: String,
    /// Scaled impact speed kappa (p(eps^2) hardly depends on it above ~30).
    #[arg(long, default_value = "100", allow_hyphen_values = true)]
    pub kappa: String,
    /// The log-spaced grid of E_tr/T_bath: MIN,MAX,COUNT.
    #[arg(long, default_value = "0.01,100,17", allow_hyphen_values = true)]
    pub ratios: String,
    /// Realizations of Eq. (3) per ratio.
    #[arg(long, default_value = "4000", allow_hyphen_values = true)]
    pub realizations: String,
    /// Seed.
    #[arg(long, default_value = "1", allow_hyphen_values = true)]
    pub seed: String,
    /// The JSON file to write.
    #[arg(long)]
    pub out: std::path::PathBuf,
}

/// Arguments of `haff demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Output directory: its run files, runs and figures replace earlier ones of the demo.
    #[arg(long, default_value = "demo")]
    pub out: std::path::PathBuf,
    /// Print only the eps(v) table of ice (what `haff demo` printed before it ran gases).
    #[arg(long)]
    pub table: bool,
}

/// Arguments of `haff run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The run file (every key: docs/guide/reference.md, `haff schema`); not with --resume.
    pub file: Option<std::path::PathBuf>,
    /// Output directory [default: the run file's name without extension; with --resume
    /// the check-point's directory].
    #[arg(long)]
    pub out: Option<std::path::PathBuf>,
    /// Save the state every K samples to DIR/checkpoint.bin.
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub checkpoint_every: Option<String>,
    /// Continue the run saved in DIR/checkpoint.bin.
    #[arg(long, value_name = "DIR", conflicts_with = "file")]
    pub resume: Option<std::path::PathBuf>,
    /// Replace the outputs of another run in the output directory.
    #[arg(long)]
    pub force: bool,
    /// End after this many samples (a run in chunks; continue with --resume).
    #[arg(
        long,
        value_name = "K",
        allow_hyphen_values = true,
        requires = "checkpoint_every"
    )]
    pub stop_after_samples: Option<String>,
    /// Check the run file as the run would before its first step (keys, ranges, particles
    /// placed, laws built) and print the run it describes as TOML, every default filled in
    /// as summary.json records it; nothing runs, nothing is written. Exit 0 or 2.
    #[arg(long, conflicts_with_all = ["resume", "out", "checkpoint_every", "force"])]
    pub check: bool,
}

/// Arguments of `haff study`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    /// The study file (base run file, seeds, [vary], [[zip]]; see docs/studies.md).
    pub file: std::path::PathBuf,
    /// Output directory [default: the study file's name without extension].
    #[arg(long)]
    pub out: Option<std::path::PathBuf>,
    /// Runs at a time (local threads), 1 ..= 4096 [default: 1].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub jobs: Option<String>,
    /// Threads per run, 1 ..= 4096 [default: 1].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub threads: Option<String>,
    /// Check-point every K samples [default: at the first sample after each minute].
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub checkpoint_every: Option<String>,
    /// Replace another study's runs and aggregates in the output directory.
    #[arg(long)]
    pub force: bool,
    /// Leave out the points whose runs do not validate (reported, exit 2 at the end)
    /// instead of refusing the study before it starts.
    #[arg(long)]
    pub keep_going: bool,
}

#[derive(Debug, Subcommand)]
enum CorCommand {
    /// eps of a viscoelastic law at scaled speeds v* (or at speeds v with --beta).
    Eps(Box<EpsArgs>),
    /// The scaled trajectory of one viscoelastic collision, integrated exactly.
    Collision(CollisionArgs),
    /// eps and duration of the linear dash-pot for given damping ratios.
    Dashpot(DashpotArgs),
    /// Series coefficients h, c, a, b of SP2008 computed by exact and high-precision algebra.
    Coefficients(CoefficientsArgs),
    /// Padé approximant [M/N] of eps(v*) from the computed series.
    Pade(PadeArgs),
}

/// Arguments of `haff cor coefficients`.
#[derive(Debug, Args)]
pub struct CoefficientsArgs {
    /// Which coefficients: h (eps = sum h_k v*^k, Table V of SP2008), c (naive eps = sum
    /// c_k A^k), a (time of maximal compression), b (maximal compression); A = v*^2.
    #[arg(long)]
    pub kind: String,
    /// Highest index k, 0 <= K <= 100 (c, a, b run the chain to 2K; a call estimated beyond
    /// about a minute is refused).
    #[arg(long, allow_hyphen_values = true)]
    pub order: String,
    /// Significant digits of the decimal values, 1 <= D <= 60.
    #[arg(long, default_value = "20", allow_hyphen_values = true)]
    pub digits: String,
    /// Order N of the trajectory series in sqrt(tau) (for convergence studies) [default:
    /// max(150, 100 + 2K)].
    #[arg(long, allow_hyphen_values = true)]
    pub trajectory_order: Option<String>,
    /// Working precision in bits (for convergence studies) [default: max(256, 128 + 4K)].
    #[arg(long, allow_hyphen_values = true)]
    pub bits: Option<String>,
}

/// Arguments of `haff cor pade`.
#[derive(Debug, Args)]
pub struct PadeArgs {
    /// Degree M of the numerator, 0 <= M <= 60.
    #[arg(long, allow_hyphen_values = true)]
    pub m: String,
    /// Degree N of the denominator, 0 <= N <= 60.
    #[arg(long, allow_hyphen_values = true)]
    pub n: String,
    /// Significant digits of the decimal values, 1 <= D <= 60.
    #[arg(long, default_value = "20", allow_hyphen_values = true)]
    pub digits: String,
}

#[derive(Debug, Subcommand)]
enum BenchCommand {
    /// Nanoseconds per evaluation of each coefficient-of-restitution law.
    Cor(BenchCorArgs),
    /// Throughput of event-driven MD of an elastic gas in 3D.
    Emd(BenchEmdArgs),
    /// Throughput of homogeneous DSMC in 3D (all cores).
    Dsmc(BenchDsmcArgs),
    /// Throughput of the rod-chain MD (two rods of Giese's Fig. 1).
    Rods(BenchRodsArgs),
    /// Size and save/load time of the check-point of an event-driven run.
    Checkpoint(BenchCheckpointArgs),
    /// Nanoseconds per particle per time step of soft-sphere MD (one core).
    SoftSphere(BenchSoftArgs),
    /// Cost of the observers of space (modes, S(k), g(r), fields) against one collision per
    /// particle of event-driven MD.
    Observers(BenchObserversArgs),
}

/// Arguments of `haff bench soft-sphere`.
#[derive(Debug, Args)]
pub struct BenchSoftArgs {
    /// A run file (3D, one kind of sphere, law = "viscoelastic" with young, poisson and
    /// dissipative_constant); its engine is taken as soft-sphere. Default: N = 1e4,
    /// phi = 0.05, Y = 1e5, nu = 0.3, A = 0.01 in units sigma = m = T = 1.
    pub run: Option<std::path::PathBuf>,
    /// Time steps timed per repeat (after as many of warm-up), 1 <= S <= 1e9.
    #[arg(long, default_value = "200", allow_hyphen_values = true)]
    pub steps: String,
    /// Timed repetitions; the median is reported.
    #[arg(long, default_value = "3", allow_hyphen_values = true)]
    pub repeats: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// Arguments of `haff bench observers`.
#[derive(Debug, Args)]
pub struct BenchObserversArgs {
    /// Number of particles, 2 <= N <= 1e8.
    #[arg(long, default_value = "100000", allow_hyphen_values = true)]
    pub particles: String,
    /// Packing fraction, 0 < phi <= 0.6 (above 0.45 the spheres of the start are grown).
    #[arg(long, default_value = "0.05", allow_hyphen_values = true)]
    pub packing_fraction: String,
    /// Dimension, 2 or 3.
    #[arg(long, default_value = "3", allow_hyphen_values = true)]
    pub dimension: String,
    /// Timed repetitions; the median is reported.
    #[arg(long, default_value = "5", allow_hyphen_values = true)]
    pub repeats: String,
    /// Largest |n|^2 of the mode shells (as `output.mode_shells`), 1 ..= 100 (default: a
    /// run's default, 3).
    #[arg(long, allow_hyphen_values = true)]
    pub mode_shells: Option<String>,
    /// Cells per side of the coarse-grained fields (as `output.fields.grid`), 3 ..= 4096
    /// (default: (N/10)^(1/D), about 10 particles per cell).
    #[arg(long, allow_hyphen_values = true)]
    pub field_grid: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// Arguments of `haff bench checkpoint`.
#[derive(Debug, Args)]
pub struct BenchCheckpointArgs {
    /// Number of particles, 2 <= N <= 1e8.
    #[arg(long, default_value = "1000000", allow_hyphen_values = true)]
    pub particles: String,
    /// Timed repetitions; the median is reported.
    #[arg(long, default_value = "3", allow_hyphen_values = true)]
    pub repeats: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// Arguments of `haff bench rods`.
#[derive(Debug, Args)]
pub struct BenchRodsArgs {
    /// Modes per rod.
    #[arg(long, default_value = "75", allow_hyphen_values = true)]
    pub modes: String,
    /// kappa = alpha l V0 / c.
    #[arg(long, default_value = "4000", allow_hyphen_values = true)]
    pub kappa: String,
    /// Collisions timed per repeat.
    #[arg(long, default_value = "300", allow_hyphen_values = true)]
    pub collisions: String,
    /// Timed repetitions; the median is reported.
    #[arg(long, default_value = "3", allow_hyphen_values = true)]
    pub repeats: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// Arguments of `haff bench emd`.
#[derive(Debug, Args)]
pub struct BenchEmdArgs {
    /// Number of particles, 2 <= N <= 1e8.
    #[arg(long, default_value = "100000", allow_hyphen_values = true)]
    pub particles: String,
    /// Packing fraction, 0 < phi <= 0.6 (above 0.45 the spheres of the start are grown).
    #[arg(long, default_value = "0.05", allow_hyphen_values = true)]
    pub packing_fraction: String,
    /// Events timed per repeat (after as many events of warm-up).
    #[arg(long, default_value = "2000000", allow_hyphen_values = true)]
    pub events: String,
    /// Timed repetitions; the median is reported.
    #[arg(long, default_value = "3", allow_hyphen_values = true)]
    pub repeats: String,
    /// The sorter of the event calendar: heap, buckets, or both (repeats interleaved, for a
    /// fair comparison).
    #[arg(long, value_enum, default_value_t = bench::CalendarChoice::Heap)]
    pub calendar: bench::CalendarChoice,
    /// Minimum cell width in diameters (>= 1).
    #[arg(long, default_value = "1", allow_hyphen_values = true)]
    pub cell_width: String,
    /// Uniform shear flow u = a y e_x with this rate a (Lees–Edwards boundaries; in units
    /// of the initial thermal speed over the diameter), 0 < |a| <= 1e3; with
    /// `--restitution` below 1 the gas settles into its steady shear flow.
    #[arg(long, allow_hyphen_values = true)]
    pub shear_rate: Option<String>,
    /// Constant coefficient of restitution, 0 < e <= 1.
    #[arg(long, default_value = "1", allow_hyphen_values = true)]
    pub restitution: String,
    /// Rough particles: the tangential restitution beta, -1 <= beta <= 1 (solid spheres,
    /// q = 0.4, spins drawn at the temperature; absent: smooth).
    #[arg(long, allow_hyphen_values = true)]
    pub tangential_restitution: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// Arguments of `haff bench dsmc`.
#[derive(Debug, Args)]
pub struct BenchDsmcArgs {
    /// Number of particles, 2 <= N <= 1e9 (default: 1e7; 1e6 for the spatial scheme, the
    /// set-up of the SPARTA comparison).
    #[arg(long, allow_hyphen_values = true)]
    pub particles: Option<String>,
    /// Packing fraction (sets the Enskog factor and the time scale), 0 < phi <= 0.6.
    #[arg(long, default_value = "0.05", allow_hyphen_values = true)]
    pub packing_fraction: String,
    /// Collisions per particle timed per repeat (after 1 of warm-up).
    #[arg(long, default_value = "2", allow_hyphen_values = true)]
    pub collisions: String,
    /// Timed repetitions; the median is reported.
    #[arg(long, default_value = "3", allow_hyphen_values = true)]
    pub repeats: String,
    /// Scheme: blocks (parallel), exact (serial) or spatial (streaming and collision cells).
    #[arg(long, value_enum, default_value_t = bench::DsmcSchemeChoice::Blocks)]
    pub scheme: bench::DsmcSchemeChoice,
    /// Spatial scheme: simulated particles per collision cell on average (SPARTA's set-up
    /// for the comparison: 15.6), 1 ..= 1000.
    #[arg(long, default_value = "15.6", allow_hyphen_values = true)]
    pub particles_per_cell: String,
    /// The law: `fast` (viscoelastic, with --beta) or a constant eps in [0, 1] (default:
    /// fast; 1, elastic, for the spatial scheme, the set-up of the SPARTA comparison).
    #[arg(long, allow_hyphen_values = true)]
    pub law: Option<String>,
    /// beta of the viscoelastic law in simulation units (T = m = sigma = 1).
    #[arg(long, default_value = "0.3", allow_hyphen_values = true)]
    pub beta: String,
    /// Worker threads (default: all cores; 1 for the serial exact scheme).
    #[arg(long, allow_hyphen_values = true)]
    pub threads: Option<String>,
    /// Rough particles: the tangential restitution beta, -1 <= beta <= 1 (solid spheres,
    /// q = 0.4, spins drawn at the temperature; absent: smooth).
    #[arg(long, allow_hyphen_values = true)]
    pub tangential_restitution: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
}

/// Arguments of `haff cor eps`.
#[derive(Debug, Args)]
pub struct EpsArgs {
    /// The law: exact, exact-naive, fast, fast-naive (-naive: the naive end-of-collision
    /// criterion); pade:M/N, series:K from the computed coefficients (M, N <= 60 and
    /// M + N <= 112; 0 <= K <= 100; high orders take up to a minute of computer algebra);
    /// pade-paper:M/N, series-paper:K as printed (Table I of MP2011: 0/3, 1/4, 2/5, 3/6;
    /// Table V of SP2008: 0 <= K <= 20).
    #[arg(long, allow_hyphen_values = true)]
    pub law: String,
    /// Scaled impact speeds v*, comma-separated, each 0 <= v* <= 1e6.
    #[arg(
        long,
        allow_hyphen_values = true,
        required_unless_present = "v",
        conflicts_with = "v"
    )]
    pub vstar: Option<String>,
    /// Impact speeds v, comma-separated, each >= 0, in the units of --units (needs --beta,
    /// or a material: --dissipative-constant and --radius with --material or
    /// --young/--poisson/--density).
    #[arg(long = "v", value_name = "V", allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Built-in material for Y, nu and density (steel, soda-lime-glass, aluminium, ice).
    #[arg(long, requires = "v", conflicts_with = "beta")]
    pub material: Option<String>,
    /// Young modulus Y in Pa (> 0); overrides --material.
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "v",
        conflicts_with = "beta"
    )]
    pub young: Option<String>,
    /// Poisson ratio nu in (-1, 0.5); overrides --material.
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "v",
        conflicts_with = "beta"
    )]
    pub poisson: Option<String>,
    /// Density in kg/m^3 (> 0); overrides --material.
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "v",
        conflicts_with = "beta"
    )]
    pub density: Option<String>,
    /// Radius of both spheres in m (> 0).
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "v",
        conflicts_with = "beta"
    )]
    pub radius: Option<String>,
    /// Dissipative constant A in s (>= 0), Eq. (15) of SP2008.
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "v",
        conflicts_with = "beta"
    )]
    pub dissipative_constant: Option<String>,
    /// Material constant beta > 0: (s/m)^(1/5) for --units si, (s/cm)^(1/5) for cgs.
    #[arg(long, allow_hyphen_values = true, requires = "v")]
    pub beta: Option<String>,
    /// Unit system of --v and --beta: si or cgs [default: si].
    #[arg(long, requires = "v")]
    pub units: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = DataFormat::Csv)]
    pub format: DataFormat,
}

/// Arguments of `haff cor collision`.
#[derive(Debug, Args)]
pub struct CollisionArgs {
    /// Scaled impact speed v*, 0 <= v* <= 1e6.
    #[arg(long, allow_hyphen_values = true)]
    pub vstar: String,
    /// End of the collision: improved (the force vanishes) or naive (the overlap vanishes).
    #[arg(long, default_value = "improved")]
    pub criterion: String,
    /// Number of trajectory points from tau = 0 to tau_c inclusive (>= 2).
    #[arg(long, default_value = "201", allow_hyphen_values = true)]
    pub points: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = DataFormat::Csv)]
    pub format: DataFormat,
}

/// Arguments of `haff cor dashpot`.
#[derive(Debug, Args)]
pub struct DashpotArgs {
    /// Damping ratios R = b/omega_0, comma-separated, each >= 0.
    #[arg(long, allow_hyphen_values = true)]
    pub damping_ratio: String,
    /// End of the collision: improved (the force vanishes) or naive (the overlap vanishes).
    #[arg(long, default_value = "improved")]
    pub criterion: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = DataFormat::Csv)]
    pub format: DataFormat,
}

/// Arguments of `haff bench cor`.
#[derive(Debug, Args)]
pub struct BenchCorArgs {
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Table)]
    pub format: ReportFormat,
    /// Timed repetitions per law; the median is reported.
    #[arg(long, default_value = "7", allow_hyphen_values = true)]
    pub repeats: String,
    /// Evaluations per repetition for the cheap laws (the exact laws get 1/10000 of them,
    /// at least 10).
    #[arg(long, default_value = "1000000", allow_hyphen_values = true)]
    pub evaluations: String,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => return clap_exit(error),
    };
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            error.report();
            error.exit_code()
        }
    }
}

/// Runs one command.
fn run(command: Command) -> CliResult {
    match command {
        Command::Cor(CorCommand::Eps(args)) => cor::eps(&args),
        Command::Cor(CorCommand::Collision(args)) => cor::collision(&args),
        Command::Cor(CorCommand::Dashpot(args)) => cor::dashpot(&args),
        Command::Cor(CorCommand::Coefficients(args)) => algebra::coefficients(&args),
        Command::Cor(CorCommand::Pade(args)) => algebra::pade(&args),
        Command::Bench(BenchCommand::Cor(args)) => bench::cor(&args),
        Command::Bench(BenchCommand::Emd(args)) => bench::emd(&args),
        Command::Bench(BenchCommand::Dsmc(args)) => bench::dsmc(&args),
        Command::Bench(BenchCommand::Rods(args)) => bench::rods(&args),
        Command::Bench(BenchCommand::Checkpoint(args)) => bench::checkpoint(&args),
        Command::Bench(BenchCommand::SoftSphere(args)) => bench::soft_sphere(&args),
        Command::Bench(BenchCommand::Observers(args)) => bench::observers(&args),
        Command::Demo(args) => demo::run(&args),
        Command::Run(args) => run::run(&args),
        Command::Study(args) => study::study(&args),
        Command::Rods(RodsCommand::Deterministic(args)) => rods::deterministic(&args),
        Command::Rods(RodsCommand::Collide(args)) => rods::collide(&args),
        Command::Rods(RodsCommand::Table(args)) => rods::table(&args),
        Command::Rods(RodsCommand::TwoRods(args)) => rods::two_rods(&args),
        Command::Rods(RodsCommand::Chain(args)) => rods::chain(&args),
        Command::Reproduce(args) => reproduce::reproduce(&args),
        Command::Schema(args) => schema::schema(&args),
    }
}

/// Help and version go out as clap prints them; usage errors become one line.
fn clap_exit(error: clap::Error) -> ExitCode {
    match error.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // Nothing sensible is left to do if the help text cannot be written.
            let _ = error.print();
            ExitCode::from(error.exit_code().clamp(0, 255) as u8)
        }
        _ => {
            let failure = CliError::usage(one_line(&error));
            failure.report();
            failure.exit_code()
        }
    }
}

/// The first paragraph of clap's message on one line, without its `error: ` prefix.
fn one_line(error: &clap::Error) -> String {
    let rendered = error.render().to_string();
    let paragraph: Vec<&str> = rendered
        .lines()
        .map(str::trim)
        .take_while(|line| !line.is_empty())
        .collect();
    let message = paragraph.join(" ");
    let message = message.strip_prefix("error: ").unwrap_or(&message);
    format!("{message} (see --help)")
}
