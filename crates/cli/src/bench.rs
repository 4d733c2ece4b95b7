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
