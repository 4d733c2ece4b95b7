//! `haff demo`: eps(v) of ice spheres with every law side by side.

use crate::bench::log_spaced;
use crate::error::{CliError, CliResult};
use crate::output::{significant, stdout, write_table};
use restitution::material::ICE_BRIDGES_BETA_CGS;
use restitution::{Restitution, ScaledForm, Viscoelastic};
use std::io::Write;

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
pub fn run() -> CliResult {
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
    let mut out = stdout();
    writeln!(
        out,
        "eps(v) of ice spheres, beta = {BETA} (s/cm)^(1/5), v* = beta^(1/2) v^(1/10)"
    )?;
    write_table(&mut out, &header, &rows)?;
    writeln!(
        out,
        "note: beta from Bridges et al. (1984) via MP2011; exact-naive ends the collision at \
         zero overlap, the others at zero force; series:K holds only for v* well below 1."
    )?;
    Ok(out.flush()?)
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
