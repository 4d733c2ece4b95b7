//! The ranges of Giese's parameters that `haff rods ...` and the Python bindings
//! (`haff.rods`) accept, written once (the type: `restitution::ranges::Range`).
//!
//! Eq. (3), deterministic and stochastic ([`crate::deterministic`], [`crate::stochastic`]):
//! [`GAMMA`], [`KAPPA`], [`STEP`], [`BATH_RATIO`], [`REALIZATIONS`]. The two-rod
//! experiment of the Hamiltonian MD ([`crate::chain::run_two_rods`]): [`TWO_RODS_GAMMA`],
//! [`TWO_RODS_KAPPA`], [`MODES`], [`C_H`].

pub use restitution::ranges::Range;

/// The length ratio gamma = l1/l2 of Eq. (3): the work of one collision grows as 1/gamma^2
/// or gamma^2 away from 1.
pub const GAMMA: Range = Range::closed("gamma", 1e-3, 1e3);

/// kappa = alpha l V0 / c of Eq. (3): the work of one collision grows as kappa.
pub const KAPPA: Range = Range::closed("kappa", 1.0, 1e5);

/// The step h kappa of the integrator of Eq. (3) (h = step / kappa).
pub const STEP: Range = Range::open("h kappa", 0.0, 1.0);

/// The energy ratio E_tr/T_bath of the noise of Eq. (5) (a cold bath, infinity, is
/// accepted besides).
pub const BATH_RATIO: Range = Range::closed("E_tr/T_bath", 1e-4, 1e6);

/// Realizations of Eq. (3) with noise in one call (a whole number).
pub const REALIZATIONS: Range = Range::closed("realizations", 1.0, 1e7);

/// The length ratio gamma = l1/l2 of the two-rod experiment.
pub const TWO_RODS_GAMMA: Range = Range::closed("gamma", 1e-2, 1e2);

/// kappa = alpha l V0 / c of the two-rod experiment.
pub const TWO_RODS_KAPPA: Range = Range::closed("kappa", 1.0, 1e6);

/// Modes per rod of the two-rod experiment (a whole number).
pub const MODES: Range = Range::closed("modes", 1.0, 2000.0);

/// The step constant c_h of the contact integrator of the rod chain.
pub const C_H: Range = Range::closed("c_h", 1e-4, 1.0);

/// Every range of this module.
pub const ALL: [Range; 9] = [
    GAMMA,
    KAPPA,
    STEP,
    BATH_RATIO,
    REALIZATIONS,
    TWO_RODS_GAMMA,
    TWO_RODS_KAPPA,
    MODES,
    C_H,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_ordered_and_finite() {
        for r in ALL {
            assert!(
                r.low.is_finite() && r.high.is_finite() && r.low < r.high,
                "{r:?}"
            );
        }
        // Whole numbers: the bounds are integers.
        for r in [REALIZATIONS, MODES] {
            assert!(r.low.fract() == 0.0 && r.high.fract() == 0.0, "{r:?}");
        }
    }

    #[test]
    fn describe_gives_the_command_wording() {
        let expected = [
            "0.001 <= gamma <= 1000",
            "1 <= kappa <= 1e5",
            "0 < h kappa < 1",
            "0.0001 <= E_tr/T_bath <= 1e6",
            "1 <= realizations <= 1e7",
            "0.01 <= gamma <= 100",
            "1 <= kappa <= 1e6",
            "1 <= modes <= 2000",
            "0.0001 <= c_h <= 1",
        ];
        for (r, text) in ALL.iter().zip(expected) {
            assert_eq!(r.describe(), text);
        }
    }
}
