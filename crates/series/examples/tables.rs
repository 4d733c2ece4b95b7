//! Compares Tables III and V of SP2008 with the computed coefficients.
//! `cargo run --release -p haff-series --example tables`
use series::coefficients::{compute, decimal, Settings};

const TABLE_III: [(f64, f64, f64); 11] = [
    (f64::NAN, 1.093362074, f64::NAN),
    (-0.2867471220, -0.5044548926, -1.153448854),
    (0.1048589922, 0.2840430192, 0.7982665553),
    (-0.04868406400, -0.1702207776, -0.5228825609),
    (0.02543116890, 0.1055007088, 0.3487426678),
    (-0.01423658282, -0.06684871371, -0.2330981260),
    (0.008337660013, 0.04303949229, 0.1566821477),
    (-0.005039737366, -0.02805108430, -0.1058187828),
    (0.003118137108, 0.01846085121, 0.07176528242),
    (-0.001964027745, -0.01224618562, -0.04885717237),
    (0.001254701962, 0.008177589114, 0.03337347194),
];
const TABLE_V: [f64; 21] = [
    1.0,
    0.0,
    -1.153448856,
    0.0,
    0.7982665581,
    0.2666666667,
    -0.5228825657,
    -0.4613795424,
    0.3487426737,
    0.4523510496,
    -0.1464314644,
    -0.3677282992,
    -0.0432489833,
    0.2818042325,
    0.1478525872,
    -0.1794420590,
    -0.1784660326,
    0.06593358882,
    0.1713586178,
    0.0252498223,
    -0.1379234986,
];

fn digits_ok(printed: f64, exact: f64) -> (bool, f64) {
    if printed == 0.0 {
        return (exact == 0.0, 0.0);
    }
    // Significant digits printed: 10.
    let scale = 10f64.powi(printed.abs().log10().floor() as i32 - 9);
    let err = (printed - exact).abs();
    (err <= 0.5 * scale * 1.0000001, err / scale)
}

fn main() {
    let c = compute(Settings::for_order(20));
    let f = |x: &series::power::Real| x.to_f64().value();
    println!("Table III: i, a (printed, computed, ok), b, c");
    for (i, (a, b, cc)) in TABLE_III.iter().enumerate() {
        let row = [(a, &c.a[i]), (b, &c.b[i]), (cc, &c.c[i])];
        let cells: Vec<String> = row
            .iter()
            .map(|(p, x)| {
                if p.is_nan() {
                    return "-".into();
                }
                let (ok, ulps) = digits_ok(**p, f(x));
                format!(
                    "{} vs {} {} ({:.1} units of the last digit)",
                    p,
                    decimal(x, 13),
                    if ok { "ok" } else { "WRONG" },
                    ulps
                )
            })
            .collect();
        println!("{i}: {}", cells.join(" | "));
    }
    println!("Table V:");
    for (k, p) in TABLE_V.iter().enumerate() {
        let (ok, ulps) = digits_ok(*p, f(&c.h[k]));
        println!(
            "h{k}: {p} vs {} {} ({ulps:.1})",
            decimal(&c.h[k], 13),
            if ok { "ok" } else { "WRONG" }
        );
    }
}
