//! `sim::reproduce` kinetic-theory items (quick mode): their numbers against independent
//! theory, with bounds of four statistical errors stated per test, and printed in ID.md.

use sim::reproduce::{find, sig, Context, Outcome};

fn run(id: &str) -> (Outcome, String) {
    let dir = std::env::temp_dir().join(format!("haff-sim-kinetic-{}-{id}", std::process::id()));
    let outcome =
        (find(id).expect("a registered id").run)(&Context::new(&dir, true)).expect("the item runs");
    let md = std::fs::read_to_string(dir.join(format!("{id}.md"))).expect("ID.md");
    let _ = std::fs::remove_dir_all(&dir);
    (outcome, md)
}

fn value(outcome: &Outcome, name: &str) -> f64 {
    outcome
        .value(name)
        .unwrap_or_else(|| panic!("no value {name}"))
}

/// Quick mode: DSMC of N = 2e4 (ln T uncertain by sqrt(2/(3N)) = 0.0058 per sample), eMD of
/// N = 1000 x 2 seeds (0.018 for the mean): Haff's law within four of those errors.
#[test]
fn kinetic_haff_follows_haffs_law() {
    let (o, md) = run("kinetic-haff");
    let dsmc = value(&o, "worst_dsmc");
    let emd = value(&o, "worst_emd_to_4t0");
    assert!(dsmc < 4.0 * 0.0058, "{dsmc}");
    assert!(emd < 4.0 * 0.018, "{emd}");
    assert!(md.contains(&sig(dsmc)) && md.contains(&sig(emd)));
}

/// a2 at eps = 0.9 against the Sonine hierarchy (gas tests, `sonine_a2_precise`:
/// -0.01579), within four batch errors; at eps = 0.3 below van Noije & Ernst's 0.1181 by
/// more than four errors (the breakdown of the first Sonine approximation).
#[test]
fn kinetic_a2_against_the_sonine_hierarchy() {
    let (o, md) = run("kinetic-a2");
    let (a, error) = (value(&o, "a2_0.9"), value(&o, "a2_0.9_error"));
    assert!((a + 0.01579).abs() < 4.0 * error, "{a} +- {error}");
    let (strong, strong_error) = (value(&o, "a2_0.3"), value(&o, "a2_0.3_error"));
    let vne = gas::theory::van_noije_ernst_a2::<3>(0.3);
    assert!(
        strong < vne - 4.0 * strong_error,
        "{strong} +- {strong_error} vs {vne}"
    );
    assert!(md.contains(&sig(a)) && md.contains(&sig(strong)));
}

/// The local exponent of viscoelastic cooling (beta = 0.01, N = 5000) over the last
/// half-decade to t = 1e8: -5/3 within four errors (ln T uncertain by sqrt(2/(3N)) =
/// 0.0115 at each end, over ln(10^0.5) = 1.15: 0.014).
#[test]
fn kinetic_viscoelastic_tail() {
    let (o, md) = run("kinetic-viscoelastic");
    let x = value(&o, "last_exponent");
    assert!((x + 5.0 / 3.0).abs() < 4.0 * 0.014, "{x}");
    assert!(md.contains(&sig(x)));
}
