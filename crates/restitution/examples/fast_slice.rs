//! Instructions per evaluation of a law over a slice, per value and with
//! `ScaledForm::eps_slice` (run under callgrind with 0 and 100 repeats: the difference /
//! 1e6 is the cost of one evaluation).
use restitution::ScaledForm;
fn main() {
    let n = 10_000;
    let v: Vec<f64> = (0..n)
        .map(|i| 1e-3 * (1e6f64).powf(i as f64 / (n - 1) as f64))
        .collect();
    let law = std::env::args().nth(1).unwrap_or("fast".into());
    let reps: usize = std::env::args().nth(2).map_or(100, |s| s.parse().unwrap());
    let slice = std::env::args().nth(3).is_some_and(|s| s == "slice");
    let form: ScaledForm = law.parse().unwrap();
    form.eps(0.5);
    let mut buf = vec![0.0; n];
    let start = std::time::Instant::now();
    for _ in 0..reps {
        if slice {
            form.eps_slice(&v, &mut buf);
        } else {
            for (o, &x) in buf.iter_mut().zip(&v) {
                *o = form.eps(x);
            }
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "{:.2} ns per value ({})",
        seconds / (reps * n) as f64 * 1e9,
        buf[3]
    );
}
