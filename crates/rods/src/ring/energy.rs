//! Translational energy of rods on a ring, and its share of the energy at equipartition.

/// Translational energy Σ m_i (v_i − V)²/2 about the centre-of-mass velocity
/// V = Σ m_i v_i / Σ m_i.
pub fn translational_energy(velocities: &[f64], masses: &[f64]) -> f64 {
    let total: f64 = masses.iter().sum();
    let drift = velocities
        .iter()
        .zip(masses)
        .map(|(v, m)| v * m)
        .sum::<f64>()
        / total;
    velocities
        .iter()
        .zip(masses)
        .map(|(v, m)| 0.5 * m * (v - drift).powi(2))
        .sum()
}

/// The share of the energy held by the translation (about the centre of mass) when N rods
/// with M modes each are at equipartition: every quadratic term of the energy holds T/2;
/// the translation has N − 1 of them (the total momentum is conserved), each rod's modes
/// 2M. So E_tr/E = ((N − 1)/2) / ((N − 1)/2 + N M). The contact energy is neglected (the
/// rods are in contact a vanishing fraction of the time).
pub fn equipartition_share(rods: usize, modes: usize) -> f64 {
    let n = rods as f64;
    0.5 * (n - 1.0) / (0.5 * (n - 1.0) + n * modes as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn translational_energy_by_hand() {
        // masses 1 and 3 at rest in the centre-of-mass frame: 9/2 + 3/2
        assert_eq!(translational_energy(&[3.0, -1.0], &[1.0, 3.0]), 6.0);
        // a common drift does not count
        assert_eq!(translational_energy(&[5.0, 1.0], &[1.0, 3.0]), 6.0);
        assert_eq!(
            translational_energy(&[2.0, 2.0, 2.0], &[1.0, 2.0, 3.0]),
            0.0
        );
    }

    #[test]
    fn equipartition_share_by_hand() {
        // two rods, one mode each: 1 translational term of 5, the two-rod 1/(4M + 1)
        assert_eq!(equipartition_share(2, 1), 0.2);
        assert_eq!(
            equipartition_share(2, 4),
            crate::chain::equipartition_time(4)
        );
        // three rods, two modes: 2 terms of 2 + 12
        assert_eq!(equipartition_share(3, 2), 1.0 / 7.0);
        // ten rods, four modes: 9 of 9 + 80
        assert!((equipartition_share(10, 4) - 9.0 / 89.0).abs() < 1e-16);
    }
}
