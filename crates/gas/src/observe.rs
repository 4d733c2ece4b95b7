//! Observables of the velocity distribution.

use crate::system::{dot, System};

pub mod green_kubo;

/// Granular temperature T = <m |c|^2> / D with c the peculiar velocity.
pub fn temperature<const D: usize>(s: &System<D>) -> f64 {
    let (mean, _) = mean_velocity(s);
    let sum: f64 = s
        .velocities
        .iter()
        .zip(&s.masses)
        .map(|(v, m)| {
            let c: [f64; D] = std::array::from_fn(|k| v[k] - mean[k]);
            m * dot(&c, &c)
        })
        .sum();
    sum / (s.len() * D) as f64
}

/// The Sonine coefficient a2 = D/(D+2) <c^4>/<c^2>^2 - 1 of the peculiar velocities.
///
/// For a mixture (unequal masses) c^2 is weighted by the mass, m c^2 (twice the kinetic
/// energy of the peculiar motion), so that a2 vanishes for Maxwellians of one temperature
/// whatever the masses; for equal masses the two definitions coincide. 0 for a gas at rest.
pub fn sonine_a2<const D: usize>(s: &System<D>) -> f64 {
    let (c2, c4) = peculiar_sums(s);
    sonine_a2_of_sums::<D>(c2, c4, s.len() as f64)
}

/// The sums of x and x^2 over the particles, x = c^2 (or m c^2 for unequal masses) of
/// the peculiar velocities c ([`sonine_a2`]).
fn peculiar_sums<const D: usize>(s: &System<D>) -> (f64, f64) {
    let (mean, _) = mean_velocity(s);
    let equal_masses = s.masses.iter().all(|&m| m == s.masses[0]);
    let (mut c2, mut c4) = (0.0, 0.0);
    for (v, &m) in s.velocities.iter().zip(&s.masses) {
        let c: [f64; D] = std::array::from_fn(|k| v[k] - mean[k]);
        let x = if equal_masses {
            dot(&c, &c)
        } else {
            m * dot(&c, &c)
        };
        c2 += x;
        c4 += x * x;
    }
    (c2, c4)
}

/// The sum of x^2 of [`sonine_a2`] (its fourth moment), which must be finite for the
/// observers.
pub fn fourth_moment_sum<const D: usize>(s: &System<D>) -> f64 {
    peculiar_sums(s).1
}

/// a2 = D/(D+2) <x^2>/<x>^2 - 1 from the sums `c2` of x and `c4` of x^2 over `n` particles
/// (x = c^2, or m c^2 for a mixture: see [`sonine_a2`]).
pub fn sonine_a2_of_sums<const D: usize>(c2: f64, c4: f64, n: f64) -> f64 {
    if c2 == 0.0 {
        // A gas at rest (a tiny system whose baths took all the energy) has no velocity
        // distribution to compare with a Maxwellian: 0 rather than 0/0.
        return 0.0;
    }
    let second = (c2 / n).powi(2);
    if second == 0.0 {
        // Peculiar speeds at the rounding of the mean (one particle, or all alike): no
        // distribution either.
        return 0.0;
    }
    D as f64 / (D as f64 + 2.0) * (c4 / n) / second - 1.0
}

/// Histogram of the scaled peculiar velocity components c = (v_k - <v>_k) / sqrt(2 T / m_i)
/// (all D components of all N particles pooled, each particle scaled with its own mass)
/// in `bins` equal bins on [-c_max, c_max]: (bin centre, density). The density is the count
/// over N D times the bin width, so it integrates to the fraction of components inside the
/// range (components outside are counted nowhere); for a Maxwellian it approaches
/// exp(-c^2) / sqrt(pi). All zero if the gas is at rest.
pub fn velocity_histogram<const D: usize>(
    s: &System<D>,
    bins: usize,
    c_max: f64,
) -> Vec<(f64, f64)> {
    let width = 2.0 * c_max / bins as f64;
    let mut counts = vec![0u64; bins];
    let t = temperature(s);
    if t > 0.0 && t.is_finite() && bins > 0 {
        let (mean, _) = mean_velocity(s);
        for (v, &m) in s.velocities.iter().zip(&s.masses) {
            let scale = (m / (2.0 * t)).sqrt();
            for k in 0..D {
                let c = (v[k] - mean[k]) * scale;
                if c >= -c_max && c < c_max {
                    let bin = ((c + c_max) / width) as usize;
                    counts[bin.min(bins - 1)] += 1;
                }
            }
        }
    }
    let total = (s.len() * D) as f64 * width;
    counts
        .iter()
        .enumerate()
        .map(|(b, &count)| {
            let centre = -c_max + (b as f64 + 0.5) * width;
            (centre, count as f64 / total)
        })
        .collect()
}

/// Kinetic energy.
pub fn kinetic_energy<const D: usize>(s: &System<D>) -> f64 {
    s.velocities
        .iter()
        .zip(&s.masses)
        .map(|(v, m)| 0.5 * m * dot(v, v))
        .sum()
}

/// Mass-weighted mean velocity and total momentum.
pub fn mean_velocity<const D: usize>(s: &System<D>) -> ([f64; D], [f64; D]) {
    let total: f64 = s.masses.iter().sum();
    let p: [f64; D] = std::array::from_fn(|k| {
        s.velocities
            .iter()
            .zip(&s.masses)
            .map(|(v, m)| m * v[k])
            .sum()
    });
    (std::array::from_fn(|k| p[k] / total), p)
}

/// The mass-weighted mean of velocities (conserved by collisions).
pub fn mass_weighted_mean<const D: usize>(velocities: &[[f64; D]], masses: &[f64]) -> [f64; D] {
    let total: f64 = masses.iter().sum();
    std::array::from_fn(|k| {
        velocities
            .iter()
            .zip(masses)
            .map(|(v, m)| m * v[k])
            .sum::<f64>()
            / total
    })
}

/// The pressure over an interval of duration `dt`: the kinetic part F n T / V plus the
/// collisional virial F sum(impulse sigma) / (D V dt) of the collisions in it (for hard
/// spheres the virial theorem's force sum becomes a sum over collisions; Allen & Tildesley,
/// *Computer Simulation of Liquids*, Sec. 2.4), with n the simulated particles and F the
/// physical particles each stands for ([`crate::Engine::weight`]). `virial_increment` is the
/// change of [`crate::Counters::virial`] over the interval; without one (dt = 0) only the
/// kinetic part.
pub fn pressure<const D: usize>(
    particles: usize,
    volume: f64,
    temperature: f64,
    weight: f64,
    virial_increment: f64,
    dt: f64,
) -> f64 {
    let collisional = if dt > 0.0 {
        weight * virial_increment / (D as f64 * volume * dt)
    } else {
        0.0
    };
    weight * particles as f64 / volume * temperature + collisional
}

/// The pressure tensor over an interval: its kinetic part and the whole (components xx,
/// yy, zz, xy, xz, yz; 2D: zz, xz, yz are 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PressureTensor {
    pub kinetic: [f64; 6],
    pub total: [f64; 6],
}

/// The pressure tensor over an interval of duration `dt` (see [`crate::shear`]): the
/// kinetic part F Σ m V_a V_b / V of the velocities V about their mean (under shear
/// [`crate::Engine::system`] gives the peculiar ones), plus the collisional part
/// F W_ab / (V dt) of the tensor virial `virial_increment` summed over the interval (none
/// for dt = 0), F the physical particles each simulated one stands for. Its trace / D is
/// [`pressure`] with the temperature of [`temperature`].
pub fn pressure_tensor<const D: usize>(
    s: &System<D>,
    weight: f64,
    virial_increment: &crate::shear::Virial,
    dt: f64,
) -> PressureTensor {
    use crate::shear::component;
    let volume = s.volume();
    let (mean, _) = mean_velocity(s);
    let mut kinetic = [0.0; 6];
    for (v, m) in s.velocities.iter().zip(&s.masses) {
        let u: [f64; D] = std::array::from_fn(|k| v[k] - mean[k]);
        for a in 0..D {
            for b in a..D {
                kinetic[component(a, b)] += m * u[a] * u[b];
            }
        }
    }
    let kinetic = kinetic.map(|x| weight * x / volume);
    let total = std::array::from_fn(|c| {
        let collisional = if dt > 0.0 {
            weight * virial_increment.0[c] / (volume * dt)
        } else {
            0.0
        };
        kinetic[c] + collisional
    });
    PressureTensor { kinetic, total }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};

    /// A gas of two masses with Gaussian velocities of one temperature (positions unused).
    fn maxwellian_mixture(n: usize, temperature: f64, seed: u64) -> System<3> {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        let masses: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 3.0 }).collect();
        let velocities = masses
            .iter()
            .map(|&m| {
                let w = (temperature / m).sqrt();
                std::array::from_fn(|_| {
                    0.25 + w * Distribution::<f64>::sample(&StandardNormal, &mut rng)
                })
            })
            .collect();
        System {
            sides: [10.0; 3],
            positions: vec![[0.0; 3]; n],
            velocities,
            radii: vec![0.5; n],
            masses,
        }
    }

    #[test]
    fn histogram_of_a_maxwellian_integrates_to_one() {
        let s = maxwellian_mixture(20_000, 2.0, 7);
        let bins = 60;
        let h = velocity_histogram(&s, bins, 5.0);
        assert_eq!(h.len(), bins);
        let width = 10.0 / bins as f64;
        assert!((h[0].0 + 5.0 - 0.5 * width).abs() < 1e-12, "{:?}", h[0]);
        assert!((h[bins - 1].0 - 5.0 + 0.5 * width).abs() < 1e-12);
        let integral: f64 = h.iter().map(|(_, d)| d * width).sum();
        assert!((integral - 1.0).abs() < 1e-12, "{integral}");
        // Close to exp(-c^2)/sqrt(pi) near the centre (60 000 components).
        for &(c, d) in &h {
            let maxwell = (-c * c).exp() / std::f64::consts::PI.sqrt();
            if c.abs() < 1.0 {
                assert!(
                    (d - maxwell).abs() < 0.05 * maxwell,
                    "{c}: {d} vs {maxwell}"
                );
            }
        }
        // One temperature for both masses: a2 near zero.
        assert!(sonine_a2(&s).abs() < 0.03, "{}", sonine_a2(&s));
    }

    #[test]
    fn histogram_ignores_components_out_of_range_and_a_gas_at_rest() {
        let mut s = maxwellian_mixture(1000, 1.0, 3);
        let h = velocity_histogram(&s, 10, 0.5);
        let integral: f64 = h.iter().map(|(_, d)| d * 0.1).sum();
        // c is Gaussian with variance 1/2: P(|c| < 0.5) = erf(0.5) = 0.5205.
        assert!((integral - 0.5205).abs() < 0.05, "{integral}");
        for v in &mut s.velocities {
            *v = [1.0, 2.0, 3.0];
        }
        assert!(velocity_histogram(&s, 10, 5.0)
            .iter()
            .all(|&(_, d)| d == 0.0));
    }
}
