//! `ScaledForm::eps_slice` is `ScaledForm::eps` value by value, bit for bit, for every kind
//! of form (inside and outside the fast law's table, at bucket edges).

use restitution::ScaledForm;

#[test]
fn slices_equal_single_evaluations() {
    let mut vstars: Vec<f64> = (0..4000)
        .map(|i| 1e-6 * 1e12f64.powf(i as f64 / 3999.0))
        .collect();
    vstars.extend((-14..14).map(|e| 2f64.powi(e)));
    vstars.extend([0.0, 1e-300, 16384.0, 16384.000000001, 1e6]);
    for law in [
        "fast",
        "fast-naive",
        "pade:3/6",
        "series:8",
        "pade-paper:1/4",
    ] {
        let form: ScaledForm = law.parse().unwrap();
        let mut out = vec![0.0; vstars.len()];
        form.eps_slice(&vstars, &mut out);
        for (&v, &e) in vstars.iter().zip(&out) {
            assert_eq!(e.to_bits(), form.eps(v).to_bits(), "{law} at v* = {v}");
        }
    }
    let exact: ScaledForm = "exact".parse().unwrap();
    let few = [0.0, 0.3, 2.0, 50.0];
    let mut out = [0.0; 4];
    exact.eps_slice(&few, &mut out);
    for (&v, &e) in few.iter().zip(&out) {
        assert_eq!(e.to_bits(), exact.eps(v).to_bits());
    }
}
