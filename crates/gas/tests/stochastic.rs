//! The event-driven engine with Giese's stochastic coefficient of restitution: energy
//! bookkeeping between translation and the per-particle baths, and equipartition.

use gas::init::monodisperse;
use gas::observe::{kinetic_energy, temperature};
use gas::Engine;
use gas::EventDriven;
use restitution::Glauber;

const MODES: u32 = 20;

fn glauber<const D: usize>(n: usize, phi: f64, bath: f64, seed: u64) -> EventDriven<D> {
    let system = monodisperse::<D>(n, phi, 1.0, 1.0, 1.0, seed).unwrap();
    let mut e = EventDriven::new(system, Box::new(Glauber::new(MODES).unwrap())).unwrap();
    e.set_baths(vec![bath; n], seed).unwrap();
    e
}

/// Translational plus bath energy, sum_i (m v_i^2 / 2 + N_modes T_i).
fn total_energy<const D: usize>(e: &mut EventDriven<D>) -> f64 {
    let baths: f64 = e.bath_temperatures().unwrap().iter().sum();
    kinetic_energy(e.system()) + f64::from(MODES) * baths
}

/// Runs `warm_up` then `samples` times n collisions; returns the means of T_kin and of
/// the bath temperature, the equipartition temperature E / (N (D/2 + N_modes)), and the
/// relative drift of the total energy.
fn relax<const D: usize>(e: &mut EventDriven<D>, warm_up: u64, samples: u32) -> [f64; 4] {
    let n = e.counts().len();
    let e0 = total_energy(e);
    e.run_collisions(warm_up * n as u64);
    let (mut kin, mut bath) = (0.0, 0.0);
    for _ in 0..samples {
        e.run_collisions(n as u64);
        kin += temperature(e.system());
        bath += e.bath_temperatures().unwrap().iter().sum::<f64>() / n as f64;
    }
    let drift = (total_energy(e) - e0).abs() / e0;
    let t_eq = e0 / (n as f64 * (0.5 * D as f64 + f64::from(MODES)));
    let s = f64::from(samples);
    eprintln!(
        "D = {D}: T_kin {:.5}, T_bath {:.5}, T_eq {t_eq:.5}, drift {drift:.1e}",
        kin / s,
        bath / s
    );
    [kin / s, bath / s, t_eq, drift]
}

/// Cold baths, hot gas (Giese's set-up): the baths take up the energy until translation
/// and vibration share it equally, T_kin = T_bath = E / (N (3/2 + N_modes)); the total
/// energy is conserved to round-off. Measured: T_kin / T_eq = 0.9962, T_bath / T_eq =
/// 1.0003, drift 3e-15.
#[test]
fn glauber_cold_baths_reach_equipartition_3d() {
    let mut e = glauber::<3>(1000, 0.05, 0.0, 3);
    let [kin, bath, t_eq, drift] = relax(&mut e, 50, 200);
    assert!(drift < 1e-12, "energy drift {drift}");
    assert!((kin / t_eq - 1.0).abs() < 0.015, "T_kin {kin} vs {t_eq}");
    assert!((bath / t_eq - 1.0).abs() < 0.003, "T_bath {bath} vs {t_eq}");
}

/// In 1D the Maxwellian at the bath temperature is invariant (Eq. (7) obeys detailed
/// balance with the collision-sampled exp(-E/T)): started there, T_kin stays at T_bath.
/// (From a cold bath the 1D ring relaxes much more slowly: collective flows decay
/// diffusively.) Measured: T_kin / T_bath = 1.004.
#[test]
fn glauber_equilibrium_is_stationary_1d() {
    let mut e = glauber::<1>(1000, 0.2, 1.0, 5);
    let [kin, bath, t_eq, drift] = relax(&mut e, 20, 200);
    assert!(drift < 1e-12, "energy drift {drift}");
    assert!(
        (kin / bath - 1.0).abs() < 0.025,
        "T_kin {kin} vs T_bath {bath}"
    );
    assert!((bath / t_eq - 1.0).abs() < 0.003, "T_bath {bath} vs {t_eq}");
}
