//! The cooling of a gas of rough spheres (3D) or disks (2D) with constant normal
//! restitution alpha and tangential restitution beta, equal particles of inertia factor q
//! (I = q m sigma^2 / 4), in the Maxwellian approximation: translational velocities and
//! angular velocities Gaussian at temperatures T_tr = m <v^2> / d and
//! T_rot = I <w^2> / d_rot (d_rot = 3 in 3D, 1 in 2D).
//!
//! Derivation (checked in the tests against Monte Carlo averages of the collision rule
//! `restitution::rough::collide` over such a gas). Per collision, with
//! eta = q (1 + beta) / (2 (1 + q)) (Luding, Huthmann, McNamara & Zippelius, Phys. Rev. E
//! 58, 3416 (1998), Eq. (4)), g_perp the tangential part of the relative velocity and
//! u = (sigma / 2) (w_i + w_j) x n the rolling part of the contact velocity:
//!
//! Delta E_tr = (m/4) [-(1 - alpha^2) g_n^2 - 4 eta (1 - eta) |g_perp|^2 + 4 eta^2 |u|^2]
//! plus a cross term in g_perp . u, and
//! Delta E_rot = m [-eta g_t . u + (eta^2 / q) |g_t|^2] with g_t = g_perp + u.
//!
//! Averaged over collisions (weight g_n): <g_n^2> = 4 T_tr / m, <|g_perp|^2> =
//! 2 (d - 1) T_tr / m, <|u|^2> = 2 (d - 1) T_rot / (q m), cross terms 0. With
//! c = 2 (d - 1), B = eta^2 / q, C = (eta / q)(1 - eta / q) and tau the collisions per
//! particle (each collision changes the energies of 2 of the N particles:
//! dT_tr / dtau = <Delta E_tr> / d, dT_rot / dtau = <Delta E_rot> / d_rot):
//!
//! dT_tr / dtau = [-(1 - alpha^2 + c eta (1 - eta)) T_tr + c B T_rot] / d,
//! dT_rot / dtau = c [B T_tr - C T_rot] / d_rot.
//!
//! In 3D (c = 4, d = d_rot = 3) these are Luding et al.'s Eqs. (7)–(8) up to the time
//! scale: (4/3) [-A T_tr + B T_rot] and (4/3) [B T_tr - C T_rot] with
//! A = (1 - alpha^2) / 4 + eta (1 - eta); the ratio r = T_rot / T_tr of the homogeneous
//! cooling state solves B r^2 + (C - A) r - B = 0 (Huthmann & Zippelius, Phys. Rev. E
//! 56, R6275 (1997); Luding et al. 1998, Eq. (10)). In 2D the same derivation gives
//! dT_tr/dtau = -[(1 - alpha^2)/2 + eta (1 - eta)] T_tr + B T_rot and
//! dT_rot/dtau = 2 [B T_tr - C T_rot].
//!
//! The approximation: the velocity distributions are Gaussians and translation and
//! rotation uncorrelated. Both fail by a few percent in the cooling state (the cumulants
//! a20, a02 and the correlation a11; Santos, Kremer & dos Santos, Phys. Fluids 23, 030604
//! (2011); Kremer, Santos & Garzó, Phys. Rev. E 90, 022205 (2014)); their first Sonine
//! approximation is [`super::rough_sonine`].

/// The Maxwellian theory of a rough gas of one kind of particle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughMaxwellian {
    /// Dimension: 2 (disks) or 3 (spheres).
    pub dimension: usize,
    pub alpha: f64,
    pub beta: f64,
    /// Inertia factor q: I = q m sigma^2 / 4.
    pub inertia: f64,
}

/// The homogeneous cooling state in the Maxwellian approximation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughHcs {
    /// T_rot / T_tr.
    pub ratio: f64,
    /// -d ln T / d(collisions per particle), the same for both temperatures.
    pub cooling_per_collision: f64,
}

impl RoughMaxwellian {
    fn rotational_dimension(&self) -> f64 {
        if self.dimension == 2 {
            1.0
        } else {
            3.0
        }
    }

    /// eta = q (1 + beta) / (2 (1 + q)).
    pub fn eta(&self) -> f64 {
        self.inertia * (1.0 + self.beta) / (2.0 * (1.0 + self.inertia))
    }

    /// The linear system d(T_tr, T_rot)/dtau = M (T_tr, T_rot) per collision per
    /// particle (module docs): M row-major.
    pub fn rates(&self) -> [[f64; 2]; 2] {
        let d = self.dimension as f64;
        let d_rot = self.rotational_dimension();
        let c = 2.0 * (d - 1.0);
        let (eta, q) = (self.eta(), self.inertia);
        let b = eta * eta / q;
        let cc = (eta / q) * (1.0 - eta / q);
        let a = 1.0 - self.alpha * self.alpha + c * eta * (1.0 - eta);
        [[-a / d, c * b / d], [c * b / d_rot, -c * cc / d_rot]]
    }

    /// The homogeneous cooling state: the ratio where both temperatures decay at the same
    /// rate. None for smooth spheres (beta = -1: rotation decouples and keeps its
    /// temperature while translation cools).
    pub fn hcs(&self) -> Option<RoughHcs> {
        if self.beta == -1.0 {
            return None;
        }
        let [[m00, m01], [m10, m11]] = self.rates();
        // r = T_rot/T_tr with (m10 + m11 r) / r = m00 + m01 r:
        // m01 r^2 + (m00 - m11) r - m10 = 0, m01, m10 > 0: one positive root.
        let (a2, a1, a0) = (m01, m00 - m11, -m10);
        let root = (a1 * a1 - 4.0 * a2 * a0).sqrt();
        let ratio = if a1 >= 0.0 {
            -2.0 * a0 / (a1 + root)
        } else {
            (root - a1) / (2.0 * a2)
        };
        Some(RoughHcs {
            ratio,
            cooling_per_collision: -(m00 + m01 * ratio),
        })
    }

    /// The temperatures after `tau` collisions per particle from (T_tr, T_rot): the exact
    /// solution of the linear system (its eigenvalues are real: the off-diagonal
    /// entries have one sign).
    pub fn evolve(&self, start: [f64; 2], tau: f64) -> [f64; 2] {
        let [[a, b], [c, d]] = self.rates();
        let half_trace = 0.5 * (a + d);
        let gap = (0.25 * (a - d) * (a - d) + b * c).sqrt();
        // exp(M tau) = e^{h tau} [cosh(g tau) I + sinh(g tau)/g (M - h I)].
        let (ch, sh_over_g) = if gap * tau.abs() < 1e-8 {
            (1.0, tau)
        } else {
            ((gap * tau).cosh(), (gap * tau).sinh() / gap)
        };
        let e = (half_trace * tau).exp();
        let [x, y] = start;
        [
            e * (ch * x + sh_over_g * ((a - half_trace) * x + b * y)),
            e * (ch * y + sh_over_g * (c * x + (d - half_trace) * y)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_distr::StandardNormal;
    use restitution::rough::{collide, Body, Tangential};

    /// Monte Carlo average of the energy changes per collision over a Maxwellian gas:
    /// pairs with Gaussian velocities (variance T_tr / m) and angular velocities
    /// (variance T_rot / I per rotational axis), uniform normals, weighted by the approach
    /// speed; returns (<dE_tr>, <dE_rot>) and their standard errors (of the ratio of sums).
    fn monte_carlo(
        theory: &RoughMaxwellian,
        t_tr: f64,
        t_rot: f64,
        draws: usize,
    ) -> [(f64, f64); 2] {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(17);
        let (m, radius, q) = (1.0, 0.5, theory.inertia);
        let moment = q * m * radius * radius;
        let rule = Tangential::new(theory.beta, None).unwrap();
        let body = Body {
            mass: m,
            radius,
            inertia: q,
        };
        let planar = theory.dimension == 2;
        // Sums of w, w x, and of w^2, w^2 x, w^2 x^2 for the ratio estimator's error.
        let (mut weights, mut sums) = (0.0, [0.0; 2]);
        let (mut weights2, mut sums2, mut squares2) = (0.0, [0.0; 2], [0.0; 2]);
        let gauss = |rng: &mut rand_pcg::Pcg64, s: f64| s * rng.sample::<f64, _>(StandardNormal);
        for _ in 0..draws {
            let mut n = [0.0; 3];
            for (k, x) in n.iter_mut().enumerate() {
                if !(planar && k == 2) {
                    *x = gauss(&mut rng, 1.0);
                }
            }
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let n = n.map(|x| x / l);
            let (sv, sw) = ((t_tr / m).sqrt(), (t_rot / moment).sqrt());
            let v: [[f64; 3]; 2] = std::array::from_fn(|_| {
                std::array::from_fn(|k| {
                    if planar && k == 2 {
                        0.0
                    } else {
                        gauss(&mut rng, sv)
                    }
                })
            });
            let w: [[f64; 3]; 2] = std::array::from_fn(|_| {
                std::array::from_fn(|k| {
                    if planar && k != 2 {
                        0.0
                    } else {
                        gauss(&mut rng, sw)
                    }
                })
            });
            let g_n: f64 = (0..3).map(|k| (v[0][k] - v[1][k]) * n[k]).sum();
            if g_n <= 0.0 {
                continue;
            }
            let out = collide(&rule, theory.alpha, [body; 2], n, v, w);
            let e = |v: &[[f64; 3]; 2], scale: f64| {
                0.5 * scale * v.iter().flatten().map(|x| x * x).sum::<f64>()
            };
            let changes = [
                e(&out.velocities, m) - e(&v, m),
                e(&out.angular, moment) - e(&w, moment),
            ];
            weights += g_n;
            weights2 += g_n * g_n;
            for s in 0..2 {
                sums[s] += g_n * changes[s];
                sums2[s] += g_n * g_n * changes[s];
                squares2[s] += g_n * g_n * changes[s] * changes[s];
            }
        }
        std::array::from_fn(|s| {
            let mean = sums[s] / weights;
            // Var(sum w x / sum w) = sum w^2 (x - mean)^2 / (sum w)^2 (the delta method).
            let spread = squares2[s] - 2.0 * mean * sums2[s] + mean * mean * weights2;
            (mean, spread.max(0.0).sqrt() / weights)
        })
    }

    /// The oracle: Monte Carlo averages of the one-collision rule over the Maxwellian gas
    /// (no formula of this module in it). Tolerance: 5 standard errors of the average.
    #[test]
    fn rates_are_the_averages_of_the_collision_rule() {
        for (dimension, alpha, beta, q) in [
            (3, 0.8, 0.4, 0.4),
            (3, 0.95, -0.5, 2.0 / 3.0),
            (2, 0.7, 0.9, 0.5),
            (2, 1.0, 0.0, 0.25),
        ] {
            let theory = RoughMaxwellian {
                dimension,
                alpha,
                beta,
                inertia: q,
            };
            let (t_tr, t_rot) = (1.3, 0.6);
            let mc = monte_carlo(&theory, t_tr, t_rot, 400_000);
            let m = theory.rates();
            let d = dimension as f64;
            let d_rot = if dimension == 2 { 1.0 } else { 3.0 };
            let predicted = [
                d * (m[0][0] * t_tr + m[0][1] * t_rot),
                d_rot * (m[1][0] * t_tr + m[1][1] * t_rot),
            ];
            for s in 0..2 {
                let (mean, error) = mc[s];
                assert!(
                    (mean - predicted[s]).abs() < 5.0 * error,
                    "d {dimension} alpha {alpha} beta {beta} part {s}: MC {mean} ± {error}, theory {}",
                    predicted[s]
                );
            }
        }
    }

    /// In 3D the ratio solves Luding et al.'s B r^2 + (C - A) r - B = 0 (their Eq. (10),
    /// coded here from the paper's A, B, C); alpha = beta = 1 is equipartition without
    /// cooling; the cooling state is a fixed point of `evolve`.
    #[test]
    fn the_cooling_state_and_its_limits() {
        for (alpha, beta, q) in [(0.9, 0.0, 0.4), (0.6, 0.7, 0.4), (0.95, -0.8, 2.0 / 3.0)] {
            let hcs = RoughMaxwellian {
                dimension: 3,
                alpha,
                beta,
                inertia: q,
            }
            .hcs()
            .unwrap();
            let eta = q * (1.0 + beta) / (2.0 * (1.0 + q));
            let a = (1.0 - alpha * alpha) / 4.0 + eta * (1.0 - eta);
            let b = eta * eta / q;
            let c = eta / q * (1.0 - eta / q);
            let r = hcs.ratio;
            assert!(
                (b * r * r + (c - a) * r - b).abs() < 1e-14,
                "{alpha} {beta}"
            );
        }
        for dimension in [2, 3] {
            let theory = RoughMaxwellian {
                dimension,
                alpha: 1.0,
                beta: 1.0,
                inertia: 0.4,
            };
            let hcs = theory.hcs().unwrap();
            assert!((hcs.ratio - 1.0).abs() < 1e-14 && hcs.cooling_per_collision.abs() < 1e-15);
            let smooth = RoughMaxwellian {
                beta: -1.0,
                alpha: 0.8,
                ..theory
            };
            assert!(smooth.hcs().is_none());
            let rough = RoughMaxwellian {
                alpha: 0.8,
                beta: 0.3,
                ..theory
            };
            let hcs = rough.hcs().unwrap();
            let [t, w] = rough.evolve([1.0, hcs.ratio], 7.0);
            let decay = (-hcs.cooling_per_collision * 7.0).exp();
            assert!((t - decay).abs() < 1e-13 && (w - hcs.ratio * decay).abs() < 1e-13);
            // From no rotation at all the ratio approaches the cooling state's.
            let [t, w] = rough.evolve([1.0, 0.0], 200.0);
            assert!(
                (w / t - hcs.ratio).abs() < 1e-9,
                "{} vs {}",
                w / t,
                hcs.ratio
            );
        }
    }
}
