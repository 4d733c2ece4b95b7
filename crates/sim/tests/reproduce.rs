//! `sim::reproduce`: the numbers each item reports (and prints in its ID.md) agree with the
//! values the library tests pin (crates/restitution/tests/laws.rs, crates/series tests,
//! docs/errata.md).

use sim::reproduce::{find, sig, Context, Outcome};
use std::path::PathBuf;

fn run(id: &str) -> (Outcome, String) {
    let dir: PathBuf =
        std::env::temp_dir().join(format!("haff-sim-reproduce-{}-{id}", std::process::id()));
    let ctx = Context::new(&dir, true);
    let entry = find(id).expect("a registered id");
    let outcome = (entry.run)(&ctx).expect("the item runs");
    let md = std::fs::read_to_string(dir.join(format!("{id}.md"))).expect("ID.md");
    let _ = std::fs::remove_dir_all(&dir);
    (outcome, md)
}

fn value(outcome: &Outcome, name: &str) -> f64 {
    outcome
        .value(name)
        .unwrap_or_else(|| panic!("no value {name}"))
}

/// The value is printed in the note, as `sig` writes it.
fn printed_in(md: &str, x: f64) {
    assert!(md.contains(&sig(x)), "{} not in the note:\n{md}", sig(x));
}

#[test]
fn mp2011_fig1_eps_at_1_25() {
    let (o, md) = run("mp2011-fig1");
    // laws::improved_law_at_vstar_1_25: exact 0.270632025426, [1/4] ~ 0.278, k_c = 10 ~ 1.85.
    let e = value(&o, "eps_exact_1_25");
    assert!((e - 0.270632025426).abs() < 1e-11, "{e}");
    assert!((value(&o, "pade_1_4_at_1_25") - 0.278).abs() < 5e-4);
    assert!((value(&o, "series_10_at_1_25") - 1.85).abs() < 5e-3);
    printed_in(&md, e);
}

#[test]
fn mp2011_fig2_asymptote_prefactor() {
    let (o, md) = run("mp2011-fig2");
    // laws::asymptotic_power_laws: eps v*^(10/3) -> (3/2)^(2/3); slope -3.2 near v* = 4.5.
    let p = value(&o, "asymptote_prefactor");
    let theory = 1.5f64.powf(2.0 / 3.0);
    assert!((p / theory - 1.0).abs() < 1e-5, "{p}");
    assert!((value(&o, "slope_at_10") + 3.3178).abs() < 1e-3);
    let at = value(&o, "slope_minus_3_2_at");
    assert!((3.8..5.0).contains(&at), "{at}");
    printed_in(&md, p);
    assert!(
        md.contains(&format!("(3/2)^(2/3) = {}", sig(theory))),
        "{md}"
    );
}

#[test]
fn mp2011_fig3_and_table1_pade_errors() {
    let (o, md) = run("mp2011-fig3");
    // docs/series-algebra.md and laws::pade_table_i_against_exact: [1/4] 8.64e-3, [3/6] 6.7145e-4.
    assert!((value(&o, "max_error_1_4") - 8.6412e-3).abs() < 2e-6);
    assert!((value(&o, "max_error_3_6") - 6.7145e-4).abs() < 2e-6);
    // laws::pade_2_5_has_a_zero_not_a_pole_at_5_68.
    assert!((value(&o, "zero_of_2_5") - 5.6801).abs() < 1e-3);
    printed_in(&md, value(&o, "max_error_3_6"));

    let (o, md) = run("mp2011-table1");
    // laws::pade_table_i_from_table_v: every printed digit within half a unit; b_3 of [0/3] = 0.
    assert!(value(&o, "worst_last_digit_units") <= 0.5);
    assert_eq!(value(&o, "b3_of_0_3"), 0.0);
    // The best pole-free order up to [18/21] is [14/17], 9.91e-7 (docs/series-algebra.md).
    assert!((value(&o, "best_error") - 9.91e-7).abs() < 1e-8);
    printed_in(&md, value(&o, "best_error"));
}

#[test]
fn sp2008_table5_h2() {
    let (o, md) = run("sp2008-table5");
    // docs/errata.md: h_2 = c_1 = -1.1534488580952887991, printed -1.153448856.
    assert!((value(&o, "h2") + 1.153_448_858_095_288_9).abs() < 1e-15);
    assert!(md.contains("-1.1534488580952887991"), "{md}");
    // laws::series_against_exact_for_small_vstar: (series - exact)/v*^2 = 2.0881e-9 at 0.05.
    assert!((value(&o, "h2_residual") - 2.088e-9).abs() < 1e-11);

    let (o, md) = run("sp2008-table3");
    assert!((value(&o, "c1") + 1.153_448_858_095_288_9).abs() < 1e-15);
    assert!(md.contains("-1.1534488580952887991"), "{md}");
}

#[test]
fn sp2008_asymptotes_and_dashpot() {
    let (o, md) = run("sp2008-fig2");
    // The naive slow-manifold constant P* = 5.158381704 (docs/collision-laws.md).
    let p = value(&o, "naive_prefactor");
    assert!((p - 5.158381704).abs() < 1e-8, "{p}");
    printed_in(&md, p);

    let (o, md) = run("sp2008-dashpot");
    // The middle branch of Eq. (12) as printed gives eps > 1 (docs/errata.md).
    assert!(value(&o, "printed_at_0_8") > 1.0);
    let c = value(&o, "corrected_at_0_8");
    assert!(c > 0.0 && c < 1.0);
    printed_in(&md, c);

    let (o, _) = run("sp2008-fig1");
    // The rubber example: eps = 0.80097 at beta v^(1/5) = 0.2 (docs/errata.md).
    assert!((value(&o, "rubber_eps") - 0.80097).abs() < 1e-5);
}
