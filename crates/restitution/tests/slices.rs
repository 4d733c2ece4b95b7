//! `ScaledForm::eps_slice` is `ScaledForm::eps` value by value, bit for bit, for every kind
//! of form (inside and outside the fast law's table, at bucket edges; the fast law's AVX2
//! path four values at a time where the processor has it).

use restitution::ScaledForm;

#[test]
fn slices_equal_single_evaluations() {
    let mut vstars: Vec<f64> = (0..4000)
        .map(|i| 1e-6 * 1e12f64.powf(i as f64 / 3999.0))
        .collect();
    vstars.extend((-14..14).map(|e| 2f64.powi(e)));
    vstars.extend([0.0, 1e-300, 16384.0, 16384.000000001, 1e6]);
    // Shuffled (lanes of one group in different buckets, some outside the table), and a
    // length that is not a multiple of four.
    let mut state = 12345u64;
    for _ in 0..4001 {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let u = (state >> 11) as f64 / (1u64 << 53) as f64;
        vstars.push(1e-6 * 1e12f64.powf(u));
    }
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
