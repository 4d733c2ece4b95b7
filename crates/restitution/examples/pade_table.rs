//! Padé approximants of every order against the exact law (issue: the paper's claim that no
//! [m/m+3] up to [25/28] improves on [3/6]). Also approximants in w = v*^(1/3) that match
//! the exact large-v* law eps -> (3/2)^(2/3) v*^(-10/3) = (3/2)^(2/3) w^(-10).
//! `cargo run --release -p haff-restitution --example pade_table`
use restitution::exact::{solve, Criterion};
use series::coefficients::{compute, Settings};
use series::pade::{pade, pade_with_asymptote, Approximant};
use series::power::{ratio, Real, Scalar};

/// Max absolute and relative error on the grid, and where the absolute one is largest.
fn errors(grid: &[(f64, f64)], f: impl Fn(f64) -> f64) -> (f64, f64, f64) {
    grid.iter()
        .fold((0.0, 0.0, 0.0), |(abs, at, rel), &(v, e)| {
            let d = (f(v) - e).abs();
            let d = if d.is_finite() { d } else { f64::INFINITY };
            if d > abs {
                (d, v, rel.max(d / e))
            } else {
                (abs, at, rel.max(d / e))
            }
        })
}

/// One table row; `to_vstar` maps the approximant's variable to v* (for the poles).
fn report(
    name: &str,
    result: Result<Approximant, impl std::fmt::Display>,
    grid: &[(f64, f64)],
    eval: &dyn Fn(&Approximant, f64) -> f64,
    limit: f64,
    to_vstar: fn(f64) -> f64,
) {
    match result {
        Ok(p) => {
            let poles: Vec<f64> = p
                .positive_real_poles(limit)
                .into_iter()
                .map(to_vstar)
                .collect();
            let (abs, at, rel) = errors(grid, |v| eval(&p, v));
            println!("{name:>10} | {abs:9.2e} at v* = {at:6.2} | {rel:9.2e} | {poles:?}");
        }
        Err(e) => println!("{name:>10} | {e}"),
    }
}

fn main() {
    let grid: Vec<(f64, f64)> = (0..=4000)
        .map(|i| 100.0 * (i as f64 / 4000.0).powi(2))
        .map(|v| (v, solve(v, Criterion::Improved).unwrap().eps))
        .collect();
    let start = std::time::Instant::now();
    let chain = compute(Settings::for_order(53));
    eprintln!("h_0..h_53 in {:?}", start.elapsed());
    println!("[m/n] in v* | max |P - eps| on [0,100] | max rel | positive poles <= 100");
    for m in 0..=25 {
        let name = format!("[{m}/{}]", m + 3);
        report(
            &name,
            pade(&chain.h, m, m + 3),
            &grid,
            &|p, v| p.eval_f64(v),
            100.0,
            |v| v,
        );
    }
    // Series in w = v*^(1/3): h_k w^(3k).
    let bits = chain.h[0].precision();
    let zero = Real::ZERO.with_precision(bits).value();
    let mut hw = vec![zero.clone(); 3 * chain.h.len()];
    for (k, h) in chain.h.iter().enumerate() {
        hw[3 * k] = h.clone();
    }
    // leading = (3/2)^(2/3): Newton on x^3 = 9/4.
    let target = ratio(9, 4, bits);
    let mut c = ratio(131, 100, bits);
    for _ in 0..20 {
        let c2 = c.mul(&c);
        c = c.sub(&c2.mul(&c).sub(&target).div(&c2.mul(&ratio(3, 1, bits))));
    }
    println!("[M/M+10] in w = v*^(1/3) with a_M/b_(M+10) = (3/2)^(2/3)");
    for m in 0..=25 {
        let name = format!("w[{m}/{}]", m + 10);
        let result = pade_with_asymptote(&hw, m, m + 10, &c);
        report(
            &name,
            result,
            &grid,
            &|p, v| p.eval_f64(v.cbrt()),
            100f64.cbrt(),
            |w| w * w * w,
        );
    }
}
