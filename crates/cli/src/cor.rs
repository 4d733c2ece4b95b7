//! `haff cor eps | collision | dashpot`: the coefficient of restitution from the command
//! line. Each command validates its arguments, calls the restitution library and writes
//! CSV or JSON.

use crate::error::{CliError, CliResult};
use crate::output::{
    number, parse_count, parse_list, parse_number, stdout, write_csv, write_json, Allowed,
    DataFormat,
};
use crate::{CollisionArgs, DashpotArgs, EpsArgs};
use restitution::dashpot::{dashpot as dashpot_outcome, DashpotCriterion};
use restitution::exact::{self, Collision, Criterion, TrajectoryPoint, VSTAR_MAX};
use restitution::material::{
    material_by_name, speed_from_vstar, ContactPair, Material, Sphere, UnitSystem,
};
use restitution::ranges;
use restitution::{Restitution, ScaledForm, Viscoelastic};
use serde::Serialize;
use std::io::Write;

/// Most trajectory points `cor collision` writes.
const MAX_POINTS: usize = 1_000_000;

/// The beta (any unit system) `cor eps --v` accepts (`restitution::ranges::BETA`).
fn beta_range() -> Allowed {
    Allowed::from(ranges::BETA)
}

/// The scaled speeds every law accepts (`restitution::ranges::VSTAR`).
fn vstar_range() -> Allowed {
    Allowed::from(ranges::VSTAR)
}

/// One row of `cor eps`.
#[derive(Debug, Serialize)]
struct EpsRow {
    #[serde(skip_serializing_if = "Option::is_none")]
    v: Option<f64>,
    vstar: f64,
    eps: f64,
}

/// The result of `cor eps`; `beta` and `units` only for physical speeds.
#[derive(Debug, Serialize)]
struct EpsTable {
    law: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    beta: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    units: Option<UnitSystem>,
    rows: Vec<EpsRow>,
}

/// `haff cor eps`: eps of a law at scaled or physical speeds.
pub fn eps(args: &EpsArgs) -> CliResult {
    let table = match &args.v {
        Some(speeds) => physical_eps(args, speeds)?,
        None => {
            forbid_without_v(args)?;
            scaled_eps(args, required(args.vstar.as_deref(), "--vstar")?)?
        }
    };
    let mut out = stdout();
    match args.format {
        DataFormat::Csv => write_eps_csv(&mut out, &table)?,
        DataFormat::Json => write_json(&mut out, &table)?,
    }
    Ok(out.flush()?)
}

/// eps at the scaled speeds of `--vstar`.
fn scaled_eps(args: &EpsArgs, vstars: &str) -> CliResult<EpsTable> {
    let vstars = parse_list("--vstar", vstars, vstar_range())?;
    let law = parse_law(&args.law)?;
    warn_outside_validity(&law, &vstars);
    let rows = vstars
        .into_iter()
        .map(|vstar| EpsRow {
            v: None,
            vstar,
            eps: law.eps(vstar),
        })
        .collect();
    Ok(EpsTable {
        law: law.to_string(),
        beta: None,
        units: None,
        rows,
    })
}

/// Warns on stderr when an approximation is evaluated beyond its validity (a Padé past a
/// pole or outside [0, 1], a series beyond its radius of convergence): the values are
/// printed, as the approximation gives them, for whoever studies its divergence.
fn warn_outside_validity(form: &ScaledForm, vstars: &[f64]) {
    let validity = form.validity();
    let beyond = vstars.iter().filter(|&&v| !validity.contains(v)).count();
    if beyond > 0 {
        eprintln!(
            "haff: warning: --law {form} is {validity}: {beyond} of the {} values printed \
             are the approximation's, not the viscoelastic law's",
            vstars.len()
        );
    }
}

/// Rejects `--beta` and `--units`, which only apply to the physical speeds of `--v`.
fn forbid_without_v(args: &EpsArgs) -> CliResult {
    let given = [("--beta", &args.beta), ("--units", &args.units)];
    match given.into_iter().find(|(_, value)| value.is_some()) {
        Some((flag, _)) => Err(CliError::argument(
            flag,
            "only allowed with --v (speeds v); with --vstar there is no material",
        )),
        None => Ok(()),
    }
}

/// eps at the physical speeds of `--v`, with `--beta` (or beta of a material) in `--units`.
fn physical_eps(args: &EpsArgs, speeds: &str) -> CliResult<EpsTable> {
    let units = parse_units(args.units.as_deref())?;
    let beta = match args.beta.as_deref() {
        Some(text) => parse_number("--beta", text, beta_range())?,
        None => {
            let beta = units.beta_from_si(material_beta(args)?);
            if !ranges::BETA.contains(beta) {
                return Err(CliError::argument(
                    "--dissipative-constant",
                    format!(
                        "with this material and radius beta = {beta:e}; allowed: {} <= beta <= {} \
                         (so that v* = 1e6 is reached at a speed v > 0)",
                        ranges::BETA.low,
                        ranges::BETA.high
                    ),
                ));
            }
            beta
        }
    };
    let v_max = speed_from_vstar(beta, VSTAR_MAX).map_err(|e| CliError::library("--beta", e))?;
    let speeds = parse_list("--v", speeds, Allowed::between("v", 0.0, v_max))?;
    let form = parse_law(&args.law)?;
    let law = Viscoelastic::new(beta, form).map_err(|e| CliError::library("--beta", e))?;
    let vstars: Vec<f64> = speeds.iter().map(|&v| law.vstar(v)).collect();
    warn_outside_validity(law.form(), &vstars);
    let rows = speeds
        .into_iter()
        .map(|v| EpsRow {
            v: Some(v),
            vstar: law.vstar(v),
            eps: law.eps(v),
        })
        .collect();
    Ok(EpsTable {
        law: law.form().to_string(),
        beta: Some(beta),
        units: Some(units),
        rows,
    })
}

/// Writes `cor eps` as CSV: `vstar,eps` or `v,vstar,eps`.
fn write_eps_csv(out: &mut impl Write, table: &EpsTable) -> CliResult {
    let physical = table.beta.is_some();
    let header: &[&str] = if physical {
        &["v", "vstar", "eps"]
    } else {
        &["vstar", "eps"]
    };
    let rows = table.rows.iter().map(|row| {
        row.v
            .map(number)
            .into_iter()
            .chain([number(row.vstar), number(row.eps)])
            .collect()
    });
    Ok(write_csv(out, header, rows)?)
}

/// The result of `cor collision`: the summary of the collision and its trajectory.
#[derive(Debug, Serialize)]
struct CollisionReport {
    vstar: f64,
    criterion: Criterion,
    tau_c: f64,
    eps: f64,
    max_compression: f64,
    time_of_max_compression: f64,
    compression_at_end: f64,
    points: Vec<TrajectoryPoint>,
}

impl CollisionReport {
    fn new(collision: Collision, points: Vec<TrajectoryPoint>) -> Self {
        CollisionReport {
            vstar: collision.vstar,
            criterion: collision.criterion,
            tau_c: collision.duration,
            eps: collision.eps,
            max_compression: collision.max_compression,
            time_of_max_compression: collision.time_of_max_compression,
            compression_at_end: collision.compression_at_end,
            points,
        }
    }

    /// The one-line summary written on stderr with the CSV output.
    fn summary(&self) -> String {
        format!(
            "collision at v* = {} ({} criterion): tau_c = {}, eps = {}, \
             max compression = {} at tau = {}, compression at end = {}",
            number(self.vstar),
            self.criterion,
            number(self.tau_c),
            number(self.eps),
            number(self.max_compression),
            number(self.time_of_max_compression),
            number(self.compression_at_end),
        )
    }
}

/// `haff cor collision`: the scaled trajectory of one collision.
pub fn collision(args: &CollisionArgs) -> CliResult {
    let vstar = parse_number("--vstar", &args.vstar, vstar_range())?;
    let criterion = parse_criterion(&args.criterion)?;
    let points = parse_count("--points", &args.points, 2, MAX_POINTS)?;
    let (collision, trajectory) =
        exact::trajectory(vstar, criterion, points).map_err(|e| CliError::library("--vstar", e))?;
    let report = CollisionReport::new(collision, trajectory);
    let mut out = stdout();
    match args.format {
        DataFormat::Csv => {
            write_csv(
                &mut out,
                &["tau", "x", "xdot", "xddot"],
                report.points.iter().map(point_cells),
            )?;
            out.flush()?;
            eprintln!("{}", report.summary());
        }
        DataFormat::Json => write_json(&mut out, &report)?,
    }
    Ok(out.flush()?)
}

/// The CSV cells of one trajectory point.
fn point_cells(point: &TrajectoryPoint) -> Vec<String> {
    [point.tau, point.x, point.xdot, point.xddot]
        .map(number)
        .to_vec()
}

/// One row of `cor dashpot`; `omega0_tc` is infinite (JSON `null`) if the particles never
/// separate.
#[derive(Debug, Serialize)]
struct DashpotRow {
    damping_ratio: f64,
    criterion: Criterion,
    eps: f64,
    omega0_tc: f64,
    separated: bool,
}

/// The result of `cor dashpot`.
#[derive(Debug, Serialize)]
struct DashpotTable {
    rows: Vec<DashpotRow>,
}

/// `haff cor dashpot`: eps and omega_0 t_c of the linear dash-pot.
pub fn dashpot(args: &DashpotArgs) -> CliResult {
    let ratios = parse_list(
        "--damping-ratio",
        &args.damping_ratio,
        Allowed::non_negative("R"),
    )?;
    let criterion = parse_criterion(&args.criterion)?;
    let rows = ratios
        .into_iter()
        .map(|ratio| dashpot_row(ratio, criterion))
        .collect::<CliResult<Vec<_>>>()?;
    let table = DashpotTable { rows };
    let mut out = stdout();
    match args.format {
        DataFormat::Csv => write_dashpot_csv(&mut out, &table)?,
        DataFormat::Json => write_json(&mut out, &table)?,
    }
    Ok(out.flush()?)
}

/// The dash-pot outcome at one damping ratio.
fn dashpot_row(ratio: f64, criterion: Criterion) -> CliResult<DashpotRow> {
    let outcome = dashpot_outcome(ratio, dashpot_criterion(criterion))
        .map_err(|e| CliError::library("--damping-ratio", e))?;
    Ok(DashpotRow {
        damping_ratio: ratio,
        criterion,
        eps: outcome.eps,
        omega0_tc: outcome.scaled_duration,
        separated: outcome.separated,
    })
}

/// Writes `cor dashpot` as CSV.
fn write_dashpot_csv(out: &mut impl Write, table: &DashpotTable) -> CliResult {
    let header = [
        "damping_ratio",
        "criterion",
        "eps",
        "omega0_tc",
        "separated",
    ];
    let rows = table.rows.iter().map(|row| {
        vec![
            number(row.damping_ratio),
            row.criterion.to_string(),
            number(row.eps),
            number(row.omega0_tc),
            row.separated.to_string(),
        ]
    });
    Ok(write_csv(out, &header, rows)?)
}

/// The dash-pot criterion with the same name as the viscoelastic one.
fn dashpot_criterion(criterion: Criterion) -> DashpotCriterion {
    match criterion {
        Criterion::Improved => DashpotCriterion::Improved,
        Criterion::Naive => DashpotCriterion::Naive,
    }
}

/// Parses `--law` (the library names the allowed laws).
fn parse_law(text: &str) -> CliResult<ScaledForm> {
    text.trim()
        .parse()
        .map_err(|e| CliError::library("--law", e))
}

/// Parses `--criterion`: improved or naive.
fn parse_criterion(text: &str) -> CliResult<Criterion> {
    text.trim()
        .parse()
        .map_err(|e| CliError::library("--criterion", e))
}

/// Parses `--units` (si when absent).
fn parse_units(text: Option<&str>) -> CliResult<UnitSystem> {
    text.map(str::parse)
        .transpose()
        .map(Option::unwrap_or_default)
        .map_err(|e| CliError::library("--units", e))
}

/// The value of an option that clap has already made mandatory in this context.
fn required<'a>(value: Option<&'a str>, flag: &str) -> CliResult<&'a str> {
    value.ok_or_else(|| CliError::argument(flag, "missing (required here)"))
}

/// beta in SI of two identical spheres of the material given on the command line
/// (Eq. 8 of MP2011, through the restitution library).
fn material_beta(args: &EpsArgs) -> CliResult<f64> {
    let a_text = args.dissipative_constant.as_deref().ok_or_else(|| {
        CliError::argument(
            "--v",
            "needs --beta, or a material: --dissipative-constant and --radius with \
             --material or --young/--poisson/--density",
        )
    })?;
    let optional = |flag: &str, text: &Option<String>, allowed: Allowed| {
        text.as_deref()
            .map(|t| parse_number(flag, t, allowed))
            .transpose()
    };
    let young = optional("--young", &args.young, Allowed::positive("Y"))?;
    let poisson = optional("--poisson", &args.poisson, Allowed::open("nu", -1.0, 0.5))?;
    let density = optional("--density", &args.density, Allowed::positive("density"))?;
    let base = args
        .material
        .as_deref()
        .map(material_by_name)
        .transpose()
        .map_err(|e| CliError::library("--material", e))?;
    let pick = |given: Option<f64>, from_base: Option<f64>, flag: &str| {
        given
            .or(from_base)
            .ok_or_else(|| CliError::argument(flag, "missing: give it or --material"))
    };
    // A = 0 is an elastic material (eps = 1 at every speed), not a viscoelastic law.
    let a = parse_number("--dissipative-constant", a_text, Allowed::positive("A"))?;
    let material = Material::new(
        base.as_ref().map_or("command line", |m| m.name.as_str()),
        pick(young, base.as_ref().map(|m| m.young_modulus), "--young")?,
        pick(poisson, base.as_ref().map(|m| m.poisson_ratio), "--poisson")?,
        pick(density, base.as_ref().map(|m| m.density), "--density")?,
        Some(a),
        "command line",
    )
    .map_err(|e| CliError::library("--material", e))?;
    let radius_text = required(args.radius.as_deref(), "--radius")?;
    let radius = parse_number("--radius", radius_text, Allowed::positive("R"))?;
    let sphere =
        Sphere::of_material(radius, &material).map_err(|e| CliError::library("--radius", e))?;
    let pair = ContactPair::new(&material, sphere, sphere)
        .map_err(|e| CliError::library("--material", e))?;
    pair.beta()
        .map_err(|e| CliError::library("--dissipative-constant", e))
}
