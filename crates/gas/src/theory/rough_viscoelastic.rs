//! The free cooling of rough particles whose normal restitution depends on the impact speed
//! (viscoelastic spheres with a constant tangential restitution beta), in the Maxwellian
//! approximation of [`super::rough`], per collision.
//!
//! Derivation. In the per-collision rates of [`super::rough`] the normal restitution enters
//! through the energy a collision takes, (m/4)(1 - alpha^2) g_n^2, averaged over collisions,
//! whose rate weight for a Maxwellian pair is g_n exp(-g_n^2 / (2 s^2)), s^2 = 2 T_tr / m:
//! with alpha(g_n), 1 - alpha^2 becomes
//!
//!   L(T_tr) = <(1 - alpha(g_n)^2)>_3 = 2 K1 - K2,  K1 = <1 + alpha>_3, K2 = <(1 + alpha)^2>_3
//!
//! over the weight g_n^3 exp(-g_n^2 / (2 s^2)) (the averages of
//! [`super::mixture`]'s laws; 1 - alpha^2 = 2 (1 + alpha) - (1 + alpha)^2). The tangential
//! terms do not involve alpha (no friction). So the rates are [`RoughMaxwellian::rates`] with
//! alpha^2 replaced by 1 - L(T_tr), now depending on T_tr, and
//!
//!   d(T_tr, T_rot)/dtau = M(T_tr) (T_tr, T_rot),   tau the collisions per particle.
//!
//! Late times. A viscoelastic alpha = 1 - O(g^(1/5)) makes L vanish as T_tr^(1/10), but the
//! tangential loss does not vanish: for -1 < beta < 1 the gas tends to the cooling state
//! of alpha = 1 and beta, T_rot/T_tr -> r(1, beta), at a constant cooling rate per collision
//! zeta(1, beta) > 0; with a collision frequency proportional to T_tr^(1/2), Haff's law
//! T ~ t^(-2) returns, approached as T^(1/10). Smooth spheres (beta = -1) and perfectly
//! rough ones (beta = 1: the tangential part elastic) keep the viscoelastic t^(-5/3)
//! (Brilliantov & Pöschel, Kinetic Theory of Granular Gases, Ch. 10, for smooth spheres).

use super::mixture::restitution_averages;
use super::rough::RoughMaxwellian;

/// A rough gas of one kind of particle (mass m) with a speed-dependent normal restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughViscoelastic {
    /// Dimension: 2 (disks) or 3 (spheres).
    pub dimension: usize,
    pub beta: f64,
    /// Inertia factor q: I = q m sigma^2 / 4.
    pub inertia: f64,
    pub mass: f64,
}

impl RoughViscoelastic {
    /// L(T_tr) = <1 - alpha(g_n)^2>_3 over the collisions of Maxwellian pairs at `t_tr`
    /// (module docs), for `eps` of the normal relative speed.
    pub fn normal_loss(&self, eps: &impl Fn(f64) -> f64, t_tr: f64) -> f64 {
        let s = (2.0 * t_tr / self.mass).sqrt();
        let (k1, k2) = restitution_averages(eps, s);
        2.0 * k1 - k2
    }

    /// The Maxwellian theory of constant restitution with the same rates at `t_tr`.
    pub fn frozen(&self, eps: &impl Fn(f64) -> f64, t_tr: f64) -> RoughMaxwellian {
        let loss = self.normal_loss(eps, t_tr).clamp(0.0, 1.0);
        RoughMaxwellian {
            dimension: self.dimension,
            alpha: (1.0 - loss).sqrt(),
            beta: self.beta,
            inertia: self.inertia,
        }
    }

    /// (T_tr, T_rot) at each of `taus` (collisions per particle, ascending, >= 0) from
    /// `start` at tau = 0: classical Runge–Kutta in (ln T_tr, ln T_rot) with steps of at
    /// most `step` collisions per particle (the rates change with T_tr only slowly, as
    /// T^(1/10); both temperatures must stay > 0: T_rot = 0 at the start is taken as
    /// 1e-300).
    pub fn evolve(
        &self,
        eps: &impl Fn(f64) -> f64,
        start: [f64; 2],
        taus: &[f64],
        step: f64,
    ) -> Vec<[f64; 2]> {
        let rate = |y: [f64; 2]| -> [f64; 2] {
            let t = [y[0].exp(), y[1].exp()];
            let [[a, b], [c, d]] = self.frozen(eps, t[0]).rates();
            [a + b * t[1] / t[0], c * t[0] / t[1] + d]
        };
        let mut y = [start[0].ln(), start[1].max(1e-300).ln()];
        let mut tau = 0.0;
        let mut out = Vec::with_capacity(taus.len());
        for &target in taus {
            while tau < target {
                let h = step.min(target - tau);
                let k1 = rate(y);
                let k2 = rate([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
                let k3 = rate([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
                let k4 = rate([y[0] + h * k3[0], y[1] + h * k3[1]]);
                for k in 0..2 {
                    y[k] += h / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k]);
                }
                tau = if target - tau <= h { target } else { tau + h };
            }
            out.push([y[0].exp(), y[1].exp()]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant alpha: L = 1 - alpha^2 and the evolution is the exact solution of the
    /// constant-alpha theory ([`RoughMaxwellian::evolve`]) to the Runge–Kutta error.
    #[test]
    fn constant_restitution_is_the_linear_theory() {
        let theory = RoughViscoelastic {
            dimension: 3,
            beta: 0.3,
            inertia: 0.4,
            mass: 1.0,
        };
        let eps = |_g: f64| 0.8;
        assert!((theory.normal_loss(&eps, 2.0) - 0.36).abs() < 1e-12);
        let exact = RoughMaxwellian {
            dimension: 3,
            alpha: 0.8,
            beta: 0.3,
            inertia: 0.4,
        };
        let taus = [1.0, 5.0, 20.0];
        let got = theory.evolve(&eps, [1.0, 0.3], &taus, 0.05);
        for (tau, g) in taus.iter().zip(&got) {
            let want = exact.evolve([1.0, 0.3], *tau);
            for k in 0..2 {
                assert!((g[k] / want[k] - 1.0).abs() < 1e-8, "{tau}: {g:?} {want:?}");
            }
        }
    }

    /// L by a second quadrature: for alpha(g) = 1 - c g (a linear law, clipped at 0) the
    /// average over g^3 exp(-g^2 / (2 s^2)) has the closed form
    /// <1 - alpha^2> = 2 c <g> - c^2 <g^2> with <g>_3 = (3/2) sqrt(pi/2) s and <g^2>_3 = 4 s^2
    /// (moments of the weight: Gamma functions), when c g stays below 1 where the weight lives.
    #[test]
    fn the_loss_average_has_the_closed_form_of_a_linear_law() {
        let theory = RoughViscoelastic {
            dimension: 3,
            beta: 0.0,
            inertia: 0.4,
            mass: 2.0,
        };
        let t = 0.5;
        let s = (2.0 * t / theory.mass).sqrt();
        let c = 0.01;
        let eps = |g: f64| 1.0 - c * g;
        let mean = 1.5 * (std::f64::consts::PI / 2.0).sqrt() * s;
        let expected = 2.0 * c * mean - c * c * 4.0 * s * s;
        let got = theory.normal_loss(&eps, t);
        assert!((got / expected - 1.0).abs() < 1e-9, "{got} vs {expected}");
    }
}
