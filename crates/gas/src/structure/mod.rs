//! Observables of space: what the homogeneous cooling state does when it breaks up. The
//! Fourier modes of the momentum and number densities at the smallest wave vectors
//! ([`modes`]), the static structure factor S(k) ([`mod@structure_factor`]) and the pair
//! correlation g(r) ([`pair`]), and coarse-grained fields on a grid ([`fields`]). They read
//! a [`crate::system::System`] only, so every spatial engine has them; none is computed
//! unless asked for.

pub mod fields;
pub mod fourier;
pub mod modes;
pub mod pair;
#[cfg(target_arch = "x86_64")]
mod pair_avx2;
pub mod structure_factor;

pub use fields::{coarse_grained_fields, Fields};

/// The side of a cubic box: the shells of wave vectors (and the pair counter's rows) are
/// those of a cube. Callers refuse other boxes first (`sim` names the output key).
pub(crate) fn cube_side<const D: usize>(system: &crate::System<D>, what: &str) -> f64 {
    assert!(
        system.is_cubic(),
        "{what} needs a cubic box (sides {:?})",
        system.sides
    );
    system.sides[0]
}
pub use fourier::{half_space_shells, Shell};
pub use modes::{hydrodynamic_modes, ModeShell};
pub use pair::{pair_correlation, StructurePoint};
pub use structure_factor::structure_factor;

/// Uniformly random points (zero velocities and radii) for the tests of the observers.
#[cfg(test)]
pub(crate) mod test_points {
    use crate::system::System;
    use rand::{Rng, SeedableRng};

    pub(crate) fn random_system<const D: usize>(n: usize, length: f64, seed: u64) -> System<D> {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        System {
            sides: [length; D],
            positions: (0..n)
                .map(|_| std::array::from_fn(|_| rng.random::<f64>() * length))
                .collect(),
            velocities: vec![[0.0; D]; n],
            radii: vec![0.0; n],
            masses: vec![1.0; n],
        }
    }
}
