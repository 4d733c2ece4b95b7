//! Gauss quadrature rules for Gaussian averages: Gauss–Hermite (weight e^(-x^2) on the line)
//! and Gauss–Laguerre (weight e^(-x) on the half-line), exact for polynomials of degree up
//! to 2n - 1. Nodes are the roots of the orthogonal polynomial, bracketed on a fine grid
//! and bisected to machine precision; weights from the standard formulas (Abramowitz & Stegun
//! 25.4.45-46).

/// Nodes and weights of an n-point rule.
#[derive(Debug, Clone, PartialEq)]
pub struct Rule {
    pub nodes: Vec<f64>,
    pub weights: Vec<f64>,
}

/// H_n(x) and H_(n-1)(x), physicists' Hermite polynomials (H_(k+1) = 2x H_k - 2k H_(k-1)).
fn hermite(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (0.0, 1.0);
    for k in 0..n {
        let next = 2.0 * x * current - 2.0 * k as f64 * previous;
        (previous, current) = (current, next);
    }
    (current, previous)
}

/// L_n(x) and L_(n-1)(x), Laguerre polynomials ((k+1) L_(k+1) = (2k+1-x) L_k - k L_(k-1)).
fn laguerre(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (0.0, 1.0);
    for k in 0..n {
        let next = ((2 * k + 1) as f64 - x) * current - k as f64 * previous;
        (previous, current) = (current, next / (k + 1) as f64);
    }
    (current, previous)
}

/// The n simple real roots of `p` in (lo, hi): sign changes on a grid, then bisection to
/// machine precision.
fn roots(n: usize, lo: f64, hi: f64, p: impl Fn(f64) -> f64) -> Vec<f64> {
    let steps = 20_000 * n;
    let h = (hi - lo) / steps as f64;
    let mut found = Vec::with_capacity(n);
    let mut a = lo;
    let mut fa = p(a);
    for k in 1..=steps {
        let b = lo + k as f64 * h;
        let fb = p(b);
        if fa == 0.0 {
            found.push(a);
        } else if fa * fb < 0.0 {
            let (mut x0, mut x1, mut f0) = (a, b, fa);
            for _ in 0..200 {
                let mid = 0.5 * (x0 + x1);
                if mid == x0 || mid == x1 {
                    break;
                }
                let fm = p(mid);
                if fm * f0 <= 0.0 {
                    x1 = mid;
                } else {
                    (x0, f0) = (mid, fm);
                }
            }
            found.push(0.5 * (x0 + x1));
        }
        (a, fa) = (b, fb);
    }
    assert_eq!(found.len(), n, "the {n} roots of the orthogonal polynomial");
    found
}

/// The n-point Gauss–Hermite rule: sum w_k f(x_k) = integral of f(x) e^(-x^2) dx.
pub fn hermite_rule(n: usize) -> Rule {
    let bound = (2.0 * n as f64 + 1.0).sqrt() + 1.0;
    let nodes = roots(n, -bound, bound, |x| hermite(n, x).0);
    // w = 2^(n-1) n! sqrt(pi) / (n^2 H_(n-1)(x)^2).
    let factorial: f64 = (1..=n).map(|k| k as f64).product();
    let weights = nodes
        .iter()
        .map(|&x| {
            let h = hermite(n, x).1;
            2f64.powi(n as i32 - 1) * factorial * std::f64::consts::PI.sqrt()
                / ((n * n) as f64 * h * h)
        })
        .collect();
    Rule { nodes, weights }
}

/// The n-point Gauss–Laguerre rule: sum w_k f(x_k) = integral over x > 0 of f(x) e^(-x) dx.
pub fn laguerre_rule(n: usize) -> Rule {
    let nodes = roots(n, 0.0, 4.0 * n as f64 + 4.0, |x| laguerre(n, x).0);
    // w = x / ((n + 1)^2 L_(n+1)(x)^2).
    let weights = nodes
        .iter()
        .map(|&x| {
            let l = laguerre(n + 1, x).0;
            x / (((n + 1) * (n + 1)) as f64 * l * l)
        })
        .collect();
    Rule { nodes, weights }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Moments of the weights, integrated exactly up to degree 2n - 1: Gamma(m + 1/2) for
    /// x^(2m) e^(-x^2) (odd moments 0), m! for x^m e^(-x). Agreement to 1e-13 of the sum of
    /// the terms' magnitudes (the round-off of the sum).
    #[test]
    fn rules_integrate_polynomials_exactly() {
        fn gamma_half(m: usize) -> f64 {
            // Gamma(m + 1/2) = (2m)! sqrt(pi) / (4^m m!).
            (0..m).fold(std::f64::consts::PI.sqrt(), |g, k| g * (k as f64 + 0.5))
        }
        for n in 1..=10 {
            let h = hermite_rule(n);
            let l = laguerre_rule(n);
            for degree in 0..2 * n {
                let sum = |r: &Rule| -> (f64, f64) {
                    let terms = r
                        .nodes
                        .iter()
                        .zip(&r.weights)
                        .map(|(x, w)| w * x.powi(degree as i32));
                    terms.fold((0.0, 0.0), |(s, a), t| (s + t, a + t.abs()))
                };
                let (q, scale) = sum(&h);
                let exact = if degree % 2 == 1 {
                    0.0
                } else {
                    gamma_half(degree / 2)
                };
                assert!(
                    (q - exact).abs() <= 1e-13 * scale,
                    "H n={n} degree {degree}: {q} vs {exact}"
                );
                let (q, scale) = sum(&l);
                let exact: f64 = (1..=degree).map(|k| k as f64).product();
                assert!(
                    (q - exact).abs() <= 1e-13 * scale,
                    "L n={n} degree {degree}: {q} vs {exact}"
                );
            }
        }
    }
}
