use restitution::{exact::{solve, Criterion}, pade::Pade, series::{Series, TABLE_V}};
fn main() {
    let n = 4000;
    let grid: Vec<f64> = (0..=n).map(|i| 100.0 * i as f64 / n as f64).collect();
    let exact: Vec<f64> = grid.iter().map(|&v| solve(v, Criterion::Improved).unwrap().eps).collect();
    for (m, nn) in [(0,3),(1,4),(2,5),(3,6)] {
        let p = Pade::table_i(m, nn).unwrap();
        let q = Pade::from_series(&TABLE_V, m, nn).unwrap();
        let (mut abs, mut at, mut rel, mut atr) = (0.0f64, 0.0, 0.0f64, 0.0);
        for (v, e) in grid.iter().zip(&exact) {
            let d = (p.eval(*v) - e).abs();
            if d > abs { abs = d; at = *v; }
            if *v <= 10.0 && d / e > rel { rel = d / e; atr = *v; }
        }
        println!("[{m}/{nn}] max abs err {abs:.3e} at v*={at:.3}; max rel (v*<=10) {rel:.3e} at {atr:.3}; poles {:?}", p.positive_poles(1e4));
        println!("   recomputed a={:?} b={:?}", q.numerator(), q.denominator());
    }
    for v in [1.25f64] { println!("1.25: exact {} [1/4] {} [3/6] {}", solve(v, Criterion::Improved).unwrap().eps, Pade::table_i(1,4).unwrap().eval(v), Pade::table_i(3,6).unwrap().eval(v)); }
    for k in [10usize, 20] { let s = Series::table_v(k).unwrap(); println!("series {k} at 1.25 {}", s.eval(1.25)); }
    for v in [0.05f64, 0.1, 0.2, 0.3, 0.5] { let e = solve(v, Criterion::Improved).unwrap().eps; println!("v*={v} series20-exact {:.3e}", Series::table_v(20).unwrap().eval(v) - e); }
    // local slopes
    for v in [3.0f64, 4.0, 5.0, 7.0, 10.0, 30.0, 100.0, 1000.0, 1e4] {
        let s = |c| { let a = solve(v*1.001, c).unwrap().eps; let b = solve(v/1.001, c).unwrap().eps; (a/b).ln()/(1.001f64*1.001).ln() };
        println!("slope at v*={v}: improved {:.6} naive {:.6}", s(Criterion::Improved), s(Criterion::Naive));
    }
}
