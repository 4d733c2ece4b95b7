//! `haff cor coefficients | pade`: the computer-algebra results of `haff-series`.

use crate::error::{CliError, CliResult};
use crate::output::{parse_count, stdout, write_csv};
use crate::{CoefficientsArgs, PadeArgs};
use series::coefficients::{compute, compute_naive, decimal, Kind, Settings};
use std::io::Write;

/// Largest index K accepted by `cor coefficients` (h_100 takes about a minute).
const MAX_ORDER: usize = 100;
/// Largest numerator or denominator degree of `cor pade`.
const MAX_DEGREE: usize = 60;
const MAX_DIGITS: usize = 60;

/// The longest `cor coefficients` may take (bounded work).
const MAX_SECONDS: f64 = 60.0;

/// The time of the chain on this machine kind, fitted to measurements of
/// `cor coefficients` (chain order K, trajectory order N, bits): (20, 150, 256) 0.32 s,
/// (20, 300, 256) 2.3 s, (20, 150, 1024) 0.50 s, (40, 300, 256) 7.1 s, (c: 100, 300, 512)
/// 33 s, (h: 100, 300, 528) 40 s; the fit is within 15 % of each.
fn estimated_seconds(settings: &Settings) -> f64 {
    0.32 * (settings.trajectory_order as f64 / 150.0).powf(2.85)
        * (settings.bits as f64 / 256.0).powf(0.32)
        * (settings.order.max(2) as f64 / 20.0).powf(1.6)
}

/// `haff cor coefficients`: CSV `k,value`, k from 0.
pub fn coefficients(args: &CoefficientsArgs) -> CliResult {
    let kind: Kind = args
        .kind
        .trim()
        .parse()
        .map_err(|e: series::Error| CliError::argument("--kind", e))?;
    let order = parse_count("--order", &args.order, 0, MAX_ORDER)?;
    let digits = parse_count("--digits", &args.digits, 1, MAX_DIGITS)?;
    let mut settings = Settings::for_order(kind.chain_order(order).max(2));
    if let Some(text) = &args.trajectory_order {
        settings.trajectory_order = parse_count("--trajectory-order", text, 20, 2000)?;
    }
    if let Some(text) = &args.bits {
        settings.bits = parse_count("--bits", text, 64, 8192)?;
    }
    let seconds = estimated_seconds(&settings);
    if seconds > MAX_SECONDS {
        return Err(CliError::argument(
            "--order",
            format!(
                "with --trajectory-order {} and --bits {} the chain needs about {seconds:.0} s; \
                 allowed: at most about {MAX_SECONDS} s (the cost grows as N^2.85 in the trajectory \
                 order, K^1.6 in the chain order and bits^0.32)",
                settings.trajectory_order, settings.bits
            ),
        ));
    }
    // a, b and c do not need the premature end of contact (the costly part at high order).
    let chain = if kind == Kind::H {
        compute(settings)
    } else {
        compute_naive(settings)
    };
    let values = chain.of(kind);
    if values.len() <= order {
        return Err(CliError::argument(
            "--order",
            "beyond what the chain provides",
        ));
    }
    let rows = values[..=order]
        .iter()
        .enumerate()
        .map(|(k, x)| vec![k.to_string(), decimal(x, digits)]);
    let mut out = stdout();
    write_csv(&mut out, &["k", "value"], rows)?;
    Ok(out.flush()?)
}

/// `haff cor pade`: CSV `i,a,b` of [M/N] (b_0 = 1), positive real poles on stderr.
pub fn pade(args: &PadeArgs) -> CliResult {
    let m = parse_count("--m", &args.m, 0, MAX_DEGREE)?;
    let n = parse_count("--n", &args.n, 0, MAX_DEGREE)?;
    let digits = parse_count("--digits", &args.digits, 1, MAX_DIGITS)?;
    let settings = Settings::for_order((m + n).max(2));
    let seconds = estimated_seconds(&settings);
    if seconds > MAX_SECONDS {
        return Err(CliError::argument(
            "--m/--n",
            format!(
                "[{m}/{n}] needs h_0..h_{} and about {seconds:.0} s; allowed: at most about \
                 {MAX_SECONDS} s, m + n <= 100",
                m + n
            ),
        ));
    }
    let chain = compute(settings);
    let approximant =
        series::pade::pade(&chain.h, m, n).map_err(|e| CliError::argument("--m/--n", e))?;
    let cell = |c: &[series::power::Real], i: usize| {
        c.get(i).map_or(String::new(), |x| decimal(x, digits))
    };
    let rows = (0..=m.max(n)).map(|i| {
        vec![
            i.to_string(),
            cell(&approximant.numerator, i),
            cell(&approximant.denominator, i),
        ]
    });
    let mut out = stdout();
    write_csv(&mut out, &["i", "a", "b"], rows)?;
    out.flush()?;
    for pole in approximant.positive_real_poles(1e6) {
        eprintln!("pole on the positive real axis at v* = {pole}");
    }
    Ok(())
}
