//! The tangential half of a collision of rough spheres (or disks): the contact points'
//! relative velocity loses its tangential part as the normal part loses its own.
//!
//! Two spheres i, j of masses m, radii a and moments of inertia I = q m a^2 (q the
//! inertia factor: 2/5 for a solid sphere, 2/3 a hollow one, 1/2 a solid disk) touch
//! along the unit normal n from i to j. Their contact points move apart with
//!
//! g = v_i - v_j + (a_i w_i + a_j w_j) x n,
//!
//! whose normal part g_n = (g . n) n is reversed by the normal law (g_n' = -eps g_n) and
//! whose tangential part g_t = g - g_n by the tangential restitution beta:
//! g_t' = -beta g_t (Huthmann & Zippelius, Phys. Rev. E 56, R6275 (1997), Eq. (2);
//! Luding, Huthmann, McNamara & Zippelius, Phys. Rev. E 58, 3416 (1998), Eqs. (1)–(4)).
//! beta = -1 is the smooth sphere (no tangential impulse), beta = 1 the perfectly rough
//! one (the tangential velocity reversed).
//!
//! An impulse P on i (and -P on j) changes g by P k_n along n and by P_t k_t across,
//! k_n = 1/m_i + 1/m_j, k_t = k_n + 1/(q_i m_i) + 1/(q_j m_j)
//! (the radii cancel: a_i^2 / I_i = 1/(q_i m_i)), so the tangential impulse that gives
//! g_t' = -beta g_t is P_t = -(1 + beta) g_t / k_t, and the kinetic energy (translation
//! and rotation) changes by -(1 - beta^2) |g_t|^2 / (2 k_t). For equal spheres this is
//! Luding et al.'s Delta v_i = -eta_t g_t with eta_t = q (1 + beta) / (2 (1 + q)).
//!
//! Walton's model (O. R. Walton, in *Particulate Two-Phase Flow*, 1993; Luding et al.
//! 1998, Eq. (5)) adds Coulomb friction: the tangential impulse is at most mu times the
//! normal one. Where the sticking impulse above exceeds it the contact slides and the
//! tangential impulse is mu |P_n| along -g_t: an effective
//! beta(gamma) = -1 + mu (1 + eps) (k_t / k_n) cot gamma, cot gamma = |g_n| / |g_t|,
//! for equal spheres -1 + mu (1 + eps) (1 + 1/q) cot gamma.

use crate::error::{Error, Result};
use crate::law::Restitution;
use crate::pairwise::Pairwise;
use crate::stochastic::StochasticRestitution;

/// The tangential rule: a tangential restitution beta in [-1, 1], and optionally
/// Coulomb's friction coefficient mu (Walton's model: beta while the contact sticks).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    beta: f64,
    friction: Option<f64>,
}

/// What the tangential rule gives at one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialImpulse {
    /// The impulse's size |P_t| >= 0 (it acts on i along -g_t).
    pub size: f64,
    /// Whether the contact slid (Coulomb's limit reached).
    pub sliding: bool,
    /// The kinetic energy (translation and rotation) the tangential impulse takes.
    pub energy_lost: f64,
}

impl Tangential {
    /// beta in [-1, 1]; friction, if given, finite and >= 0 (and then beta > -1: with
    /// beta = -1 the contact never sticks, so friction is all there is: refused as
    /// ambiguous, as `collision.friction` with the smooth default is).
    pub fn new(beta: f64, friction: Option<f64>) -> Result<Self> {
        if !(beta.is_finite() && (-1.0..=1.0).contains(&beta)) {
            return Err(Error::out_of_range(
                "tangential_restitution",
                beta,
                "-1 <= beta <= 1 (-1: smooth)",
            ));
        }
        if let Some(mu) = friction {
            if !(mu.is_finite() && mu >= 0.0) {
                return Err(Error::out_of_range(
                    "friction",
                    mu,
                    "a finite friction coefficient >= 0",
                ));
            }
            if beta == -1.0 {
                return Err(Error::out_of_range(
                    "friction",
                    mu,
                    "no friction for smooth spheres (tangential_restitution = -1): give \
                     the tangential restitution of sticking contacts",
                ));
            }
        }
        Ok(Tangential { beta, friction })
    }

    pub fn beta(&self) -> f64 {
        self.beta
    }

    pub fn friction(&self) -> Option<f64> {
        self.friction
    }

    /// The tangential impulse at a contact whose points slide past each other at
    /// `tangential_speed` |g_t|, after a normal impulse of size `normal_impulse` |P_n|,
    /// with `k_t` = 1/m_i + 1/m_j + 1/(q_i m_i) + 1/(q_j m_j) (module docs).
    #[inline]
    pub fn impulse(
        &self,
        tangential_speed: f64,
        normal_impulse: f64,
        k_t: f64,
    ) -> TangentialImpulse {
        let sticking = (1.0 + self.beta) * tangential_speed / k_t;
        let (size, sliding) = match self.friction {
            Some(mu) if mu * normal_impulse < sticking => (mu * normal_impulse, true),
            _ => (sticking, false),
        };
        TangentialImpulse {
            size,
            sliding,
            energy_lost: size * tangential_speed - 0.5 * size * size * k_t,
        }
    }

    /// The effective tangential restitution of a contact: -g_t'/g_t (= beta when it sticks).
    pub fn effective_beta(&self, tangential_speed: f64, normal_impulse: f64, k_t: f64) -> f64 {
        let p = self.impulse(tangential_speed, normal_impulse, k_t);
        p.size * k_t / tangential_speed - 1.0
    }
}

/// A tangential rule per pair of particle kinds (a mixture whose pairs differ in
/// roughness): kinds named by (radius, mass) as in [`Pairwise`], rules symmetric.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentialPairs {
    kinds: Vec<(f64, f64)>,
    /// Row-major, kinds x kinds.
    rules: Vec<Tangential>,
}

impl TangentialPairs {
    /// Kinds (radius, mass), distinct, and `rules[a][b]` (square, symmetric).
    pub fn new(kinds: Vec<(f64, f64)>, rules: Vec<Vec<Tangential>>) -> Result<Self> {
        let s = kinds.len();
        if s == 0 || rules.len() != s || rules.iter().any(|row| row.len() != s) {
            return Err(Error::out_of_range(
                "tangential_restitution",
                rules.len(),
                &format!("a square matrix with one row per kind ({s})"),
            ));
        }
        for a in 0..s {
            if kinds[..a].contains(&kinds[a]) {
                return Err(Error::out_of_range(
                    "kinds",
                    format!("{:?}", kinds[a]),
                    "kinds that differ in radius or mass",
                ));
            }
            for (b, rule) in rules[a].iter().enumerate() {
                if *rule != rules[b][a] {
                    return Err(Error::out_of_range(
                        &format!("tangential_restitution[{a}][{b}]"),
                        rule.beta,
                        "a symmetric matrix",
                    ));
                }
            }
        }
        Ok(TangentialPairs {
            kinds,
            rules: rules.into_iter().flatten().collect(),
        })
    }

    /// The kinds, (radius, mass) each.
    pub fn kinds(&self) -> &[(f64, f64)] {
        &self.kinds
    }

    /// The index of the kind of a particle of `radius` and `mass`.
    pub fn kind_of(&self, radius: f64, mass: f64) -> Option<usize> {
        self.kinds.iter().position(|&k| k == (radius, mass))
    }

    /// The rule of kinds `a` and `b`.
    #[inline]
    pub fn rule(&self, a: usize, b: usize) -> &Tangential {
        &self.rules[a * self.kinds.len() + b]
    }
}

/// A law of rough spheres: any normal law (constant, dash-pot, viscoelastic, pairwise)
/// and the tangential rule — one for all pairs, or one per pair of kinds — which
/// engines take through [`Restitution::tangential`] and
/// [`Restitution::tangential_pairs`].
#[derive(Debug, Clone)]
pub struct Rough {
    normal: Box<dyn Restitution>,
    tangential: Tangential,
    pairs: Option<TangentialPairs>,
}

impl Rough {
    /// Refuses a stochastic normal law (its baths take the normal energy only).
    pub fn new(normal: Box<dyn Restitution>, tangential: Tangential) -> Result<Self> {
        if normal.stochastic().is_some() {
            return Err(Error::out_of_range(
                "tangential_restitution",
                tangential.beta,
                "-1 (smooth) with a stochastic law",
            ));
        }
        Ok(Rough {
            normal,
            tangential,
            pairs: None,
        })
    }

    /// A rule per pair of kinds (`tangential()` is then the first kind's with itself).
    pub fn with_pairs(normal: Box<dyn Restitution>, pairs: TangentialPairs) -> Result<Self> {
        let first = *pairs.rule(0, 0);
        let mut law = Rough::new(normal, first)?;
        law.pairs = Some(pairs);
        Ok(law)
    }
}

impl Restitution for Rough {
    #[inline]
    fn eps(&self, speed: f64) -> f64 {
        self.normal.eps(speed)
    }
    fn duration(&self, speed: f64) -> Option<f64> {
        self.normal.duration(speed)
    }
    fn describe(&self) -> String {
        if let Some(pairs) = &self.pairs {
            let s = pairs.kinds.len();
            let betas: Vec<String> = (0..s)
                .flat_map(|a| (a..s).map(move |b| (a, b)))
                .map(|(a, b)| format!("{a}-{b}: {}", pairs.rule(a, b).beta))
                .collect();
            return format!(
                "{}, rough (beta {})",
                self.normal.describe(),
                betas.join(", ")
            );
        }
        let friction = self
            .tangential
            .friction
            .map_or(String::new(), |mu| format!(", friction mu = {mu}"));
        format!(
            "{}, rough (beta = {}{friction})",
            self.normal.describe(),
            self.tangential.beta
        )
    }
    fn box_clone(&self) -> Box<dyn Restitution> {
        Box::new(self.clone())
    }
    fn stochastic(&self) -> Option<&dyn StochasticRestitution> {
        None
    }
    fn pairwise(&self) -> Option<&Pairwise> {
        self.normal.pairwise()
    }
    fn tangential(&self) -> Option<&Tangential> {
        Some(&self.tangential)
    }
    fn tangential_pairs(&self) -> Option<&TangentialPairs> {
        self.pairs.as_ref()
    }
}

/// One sphere at a contact: mass, radius, inertia factor q (I = q m a^2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    pub mass: f64,
    pub radius: f64,
    pub inertia: f64,
}

/// The velocities of a pair after a rough collision (three components; disks in the
/// plane z = 0 have angular velocities along z only and stay there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    pub velocities: [[f64; 3]; 2],
    pub angular: [[f64; 3]; 2],
    pub energy_lost: f64,
    pub sliding: bool,
}

/// The full rough collision of i and j with normal restitution `eps`: the reference
/// rule (engines apply the same algebra in their own layout; their tests compare with
/// this one). `n` the unit normal from i to j, velocities `v`, angular velocities `w`.
pub fn collide(
    tangential: &Tangential,
    eps: f64,
    bodies: [Body; 2],
    n: [f64; 3],
    v: [[f64; 3]; 2],
    w: [[f64; 3]; 2],
) -> Outcome {
    let [bi, bj] = bodies;
    let spin: [f64; 3] = std::array::from_fn(|k| bi.radius * w[0][k] + bj.radius * w[1][k]);
    let roll = cross(&spin, &n);
    let g: [f64; 3] = std::array::from_fn(|k| v[0][k] - v[1][k] + roll[k]);
    let g_n = dot(&g, &n);
    let k_n = 1.0 / bi.mass + 1.0 / bj.mass;
    let k_t = k_n + 1.0 / (bi.inertia * bi.mass) + 1.0 / (bj.inertia * bj.mass);
    // Approaching: g_n > 0 (i moves towards j along n).
    let p_n = (1.0 + eps) * g_n / k_n;
    let g_t: [f64; 3] = std::array::from_fn(|k| g[k] - g_n * n[k]);
    let speed_t = dot(&g_t, &g_t).sqrt();
    let t = tangential.impulse(speed_t, p_n.abs(), k_t);
    let scale = if speed_t > 0.0 { t.size / speed_t } else { 0.0 };
    // The impulse on i: -p_n n - |P_t| g_t / |g_t|.
    let p: [f64; 3] = std::array::from_fn(|k| -p_n * n[k] - scale * g_t[k]);
    // n x P: the normal part of P has no torque (taken out exactly, not by rounding).
    let torque = cross(&n, &g_t.map(|x| -scale * x));
    Outcome {
        velocities: [
            std::array::from_fn(|k| v[0][k] + p[k] / bi.mass),
            std::array::from_fn(|k| v[1][k] - p[k] / bj.mass),
        ],
        angular: [
            std::array::from_fn(|k| w[0][k] + torque[k] / (bi.inertia * bi.mass * bi.radius)),
            std::array::from_fn(|k| w[1][k] + torque[k] / (bj.inertia * bj.mass * bj.radius)),
        ],
        energy_lost: 0.5 * (1.0 - eps * eps) * g_n * g_n / k_n + t.energy_lost,
        sliding: t.sliding,
    }
}

#[inline]
pub fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn energy(bodies: &[Body; 2], v: &[[f64; 3]; 2], w: &[[f64; 3]; 2]) -> f64 {
        (0..2)
            .map(|s| {
                let b = bodies[s];
                let inertia = b.inertia * b.mass * b.radius * b.radius;
                0.5 * b.mass * dot(&v[s], &v[s]) + 0.5 * inertia * dot(&w[s], &w[s])
            })
            .sum()
    }

    fn bodies() -> [Body; 2] {
        [
            Body {
                mass: 1.3,
                radius: 0.7,
                inertia: 0.4,
            },
            Body {
                mass: 0.6,
                radius: 0.45,
                inertia: 2.0 / 3.0,
            },
        ]
    }

    fn contact() -> ([f64; 3], [[f64; 3]; 2], [[f64; 3]; 2]) {
        let n = {
            let r = [0.3, -0.5, 0.8];
            let l = dot(&r, &r).sqrt();
            r.map(|x| x / l)
        };
        let v = [[0.9, -0.4, 1.1], [-0.2, 0.3, -0.7]];
        let w = [[1.5, -0.8, 0.2], [0.1, 2.2, -1.3]];
        (n, v, w)
    }

    /// The oracle is the definition itself: momentum and the angular momentum about the
    /// contact point are conserved, the contact's relative velocity becomes
    /// (-eps g_n, -beta g_t), and the energy lost is what the kinetic energies say.
    #[test]
    fn the_contact_velocity_follows_the_rule_and_momenta_are_kept() {
        let (n, v, w) = contact();
        let b = bodies();
        for (eps, beta) in [(0.8, 0.3), (1.0, 1.0), (0.5, -1.0), (0.9, -0.6)] {
            let rule = Tangential::new(beta, None).unwrap();
            let out = collide(&rule, eps, b, n, v, w);
            let contact_velocity = |v: &[[f64; 3]; 2], w: &[[f64; 3]; 2]| {
                let spin: [f64; 3] =
                    std::array::from_fn(|k| b[0].radius * w[0][k] + b[1].radius * w[1][k]);
                let roll = cross(&spin, &n);
                let g: [f64; 3] = std::array::from_fn(|k| v[0][k] - v[1][k] + roll[k]);
                let g_n = dot(&g, &n);
                (g_n, std::array::from_fn::<f64, 3, _>(|k| g[k] - g_n * n[k]))
            };
            let (g_n, g_t) = contact_velocity(&v, &w);
            let (g_n2, g_t2) = contact_velocity(&out.velocities, &out.angular);
            assert!(
                (g_n2 + eps * g_n).abs() < 1e-14,
                "normal: {g_n2} vs {}",
                -eps * g_n
            );
            for k in 0..3 {
                assert!((g_t2[k] + beta * g_t[k]).abs() < 1e-14, "tangential {k}");
                let momentum = |v: &[[f64; 3]; 2]| b[0].mass * v[0][k] + b[1].mass * v[1][k];
                assert!((momentum(&out.velocities) - momentum(&v)).abs() < 1e-14);
            }
            // Angular momentum of i about its contact point: I w_i is changed by the
            // torque of the impulse, m_i (a_i n) x v_i by the impulse itself: the sum of
            // each sphere's spin and the orbital part about the contact is kept.
            let about_contact = |v: &[[f64; 3]; 2], w: &[[f64; 3]; 2], s: usize| {
                let (bs, sign) = (b[s], if s == 0 { 1.0 } else { -1.0 });
                let arm = n.map(|x| -sign * bs.radius * x);
                let orbital = cross(&arm, &v[s].map(|x| bs.mass * x));
                let inertia = bs.inertia * bs.mass * bs.radius * bs.radius;
                std::array::from_fn::<f64, 3, _>(|k| orbital[k] + inertia * w[s][k])
            };
            for s in 0..2 {
                let (before, after) = (
                    about_contact(&v, &w, s),
                    about_contact(&out.velocities, &out.angular, s),
                );
                for k in 0..3 {
                    assert!((before[k] - after[k]).abs() < 1e-13, "sphere {s} axis {k}");
                }
            }
            let lost = energy(&b, &v, &w) - energy(&b, &out.velocities, &out.angular);
            assert!(
                (lost - out.energy_lost).abs() < 1e-13,
                "{lost} vs {}",
                out.energy_lost
            );
            if eps == 1.0 && beta == 1.0 {
                assert!(lost.abs() < 1e-14, "perfectly rough and elastic: {lost}");
            }
        }
    }

    /// beta = -1 is the smooth collision: no tangential impulse, spins unchanged, the
    /// velocities those of the smooth rule with the same bits.
    #[test]
    fn beta_minus_one_is_the_smooth_sphere() {
        let (n, v, w) = contact();
        let b = bodies();
        let out = collide(&Tangential::new(-1.0, None).unwrap(), 0.7, b, n, v, w);
        assert_eq!(out.angular, w);
        let g_n: f64 = (0..3).map(|k| (v[0][k] - v[1][k]) * n[k]).sum();
        let reduced = b[0].mass * b[1].mass / (b[0].mass + b[1].mass);
        let p = 1.7 * reduced * g_n;
        for k in 0..3 {
            assert!((out.velocities[0][k] - (v[0][k] - p / b[0].mass * n[k])).abs() < 1e-15);
        }
    }

    /// Walton: the contact slides exactly when (1 + beta) |g_t| / k_t > mu |P_n|, and the
    /// effective beta is then -1 + mu (1 + eps) (k_t / k_n) cot gamma (the oracle: the
    /// formula of Luding et al. 1998, Eq. (5), written for unequal spheres).
    #[test]
    fn walton_friction_slides_below_the_sticking_angle() {
        let (n, v, w) = contact();
        let b = bodies();
        let k_n = 1.0 / b[0].mass + 1.0 / b[1].mass;
        let k_t = k_n + 1.0 / (b[0].inertia * b[0].mass) + 1.0 / (b[1].inertia * b[1].mass);
        let (eps, beta) = (0.8, 0.4);
        for mu in [0.0, 0.05, 0.2, 1.0, 10.0] {
            let rule = Tangential::new(beta, Some(mu)).unwrap();
            let out = collide(&rule, eps, b, n, v, w);
            let spin: [f64; 3] =
                std::array::from_fn(|k| b[0].radius * w[0][k] + b[1].radius * w[1][k]);
            let roll = cross(&spin, &n);
            let g: [f64; 3] = std::array::from_fn(|k| v[0][k] - v[1][k] + roll[k]);
            let g_n = dot(&g, &n);
            let g_t: [f64; 3] = std::array::from_fn(|k| g[k] - g_n * n[k]);
            let cot = g_n.abs() / dot(&g_t, &g_t).sqrt();
            let walton = -1.0 + mu * (1.0 + eps) * (k_t / k_n) * cot;
            let expected = walton.min(beta);
            let effective =
                rule.effective_beta(dot(&g_t, &g_t).sqrt(), (1.0 + eps) * g_n / k_n, k_t);
            assert!(
                (effective - expected).abs() < 1e-13,
                "mu {mu}: {effective} vs {expected}"
            );
            assert_eq!(out.sliding, walton < beta, "mu {mu}");
            let lost = energy(&b, &v, &w) - energy(&b, &out.velocities, &out.angular);
            assert!((lost - out.energy_lost).abs() < 1e-13);
            assert!(lost >= 0.0);
        }
    }

    #[test]
    fn bad_parameters_name_the_key() {
        for beta in [-1.1, 1.01, f64::NAN] {
            let e = Tangential::new(beta, None).unwrap_err().to_string();
            assert!(e.contains("tangential_restitution"), "{e}");
        }
        for mu in [-0.1, f64::INFINITY] {
            let e = Tangential::new(0.0, Some(mu)).unwrap_err().to_string();
            assert!(e.contains("friction"), "{e}");
        }
        let e = Tangential::new(-1.0, Some(0.3)).unwrap_err().to_string();
        assert!(e.contains("friction") && e.contains("smooth"), "{e}");
    }
}
