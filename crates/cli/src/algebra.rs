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
    let chain = compute(Settings::for_order((m + n).max(2)));
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
