//! `haff cor coefficients | pade`: the computer-algebra results of `haff-series`.

use crate::error::{CliError, CliResult};
use crate::output::{parse_count, stdout, write_csv};
use crate::{CoefficientsArgs, PadeArgs};
use series::coefficients::{
    compute, decimal, of_kind, Kind, Settings, MAX_DIGITS, MAX_ORDER, MAX_SECONDS,
};
use series::pade::MAX_DEGREE;
use std::io::Write;

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
    let seconds = settings.estimated_seconds();
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
    let values = of_kind(kind, order, settings).map_err(|e| CliError::argument("--order", e))?;
    let rows = values
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
    let seconds = settings.estimated_seconds();
    if seconds > MAX_SECONDS {
        return Err(CliError::argument(
            "--m/--n",
            format!(
                "[{m}/{n}] needs h_0..h_{} and about {seconds:.0} s; allowed: at most about \
                 {MAX_SECONDS} s, m + n <= {}",
                m + n,
                restitution::series::max_chain_order()
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
