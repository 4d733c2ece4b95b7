//! `haff bench ...`: timing measurements, one file per benchmark. Each reports medians of
//! repeats (and min, max), as a table or JSON.

mod checkpoint;
mod cor;
mod dsmc;
mod emd;
mod observers;
mod rods;
mod soft;

pub use checkpoint::checkpoint;
pub use cor::{cor, log_spaced};
pub use dsmc::dsmc;
pub use emd::emd;
pub use observers::observers;
pub use rods::rods;
pub use soft::soft_sphere;

/// `haff bench emd --calendar`: which sorters to time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CalendarChoice {
    Heap,
    Buckets,
    /// Both, repeats interleaved.
    Both,
}

/// `haff bench dsmc --scheme`: the homogeneous DSMC scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DsmcSchemeChoice {
    /// Parallel blocks.
    Blocks,
    /// The exact process over all pairs (serial).
    Exact,
    /// Spatial DSMC: streaming, sorting into collision cells, collisions in every cell.
    Spatial,
}

/// `--packing-fraction` of the bench gases (3D), 1e-6 ..= 0.6: above 0.45 the spheres of a
/// start are grown (`gas::init`).
pub(crate) fn packing_fraction(text: &str) -> crate::CliResult<f64> {
    crate::output::parse_number(
        "--packing-fraction",
        text,
        crate::output::Allowed::between("phi", 1e-6, gas::init::packing_limit(3)),
    )
}

/// [median, min, max] of a non-empty sample.
pub(crate) fn median_min_max(mut sample: Vec<f64>) -> [f64; 3] {
    sample.sort_by(f64::total_cmp);
    let n = sample.len();
    let median = (sample[(n - 1) / 2] + sample[n / 2]) / 2.0;
    [median, sample[0], sample[n - 1]]
}

/// `--tangential-restitution`: the law made rough (None: smooth, the law as given).
pub(crate) fn rough_law(
    law: Box<dyn restitution::Restitution>,
    beta: &Option<String>,
) -> crate::CliResult<(Box<dyn restitution::Restitution>, bool)> {
    let Some(text) = beta else {
        return Ok((law, false));
    };
    let beta = crate::output::parse_number(
        "--tangential-restitution",
        text,
        crate::output::Allowed::between("tangential restitution", -1.0, 1.0),
    )?;
    let rule = restitution::rough::Tangential::new(beta, None)
        .map_err(|e| crate::CliError::argument("--tangential-restitution", e))?;
    let rough = restitution::rough::Rough::new(law, rule)
        .map_err(|e| crate::CliError::argument("--tangential-restitution", e))?;
    Ok((Box::new(rough), true))
}

/// Solid spheres' spins at the temperature of the gas's start (T = 1), for a rough bench.
pub(crate) fn spin<const D: usize>(engine: &mut dyn gas::Engine<D>, seed: u64) -> crate::CliResult {
    let system = engine.system().clone();
    let rotation = gas::rotation::Rotation::thermal(&system, vec![0.4; system.len()], 1.0, seed);
    engine
        .set_rotation(Some(rotation))
        .map_err(|e| crate::CliError::argument("--tangential-restitution", e))
}
