//! Soft-sphere MD beyond one kind of sphere and beyond 3D: contacts of unlike spheres
//! against the exact law of their pair, and the conservation laws of mixtures in 1D, 2D and
//! 3D (momentum exactly, kinetic + elastic + lost energy to the integrator's order).

use gas::init::{polydisperse, Species};
use gas::soft::accuracy::isolated_contact_eps;
use gas::soft::contact::ViscoelasticMaterial;
use gas::{Engine, SoftSphere, SoftSphereOptions, System};
use restitution::exact::{solve, Criterion};

const YOUNG: f64 = 1e4;
const POISSON: f64 = 0.3;

/// A head-on contact of unlike spheres (radii 0.5 and 0.8, masses 1 and 3) has the eps of
/// the exact law at the pair's v* = beta^(1/2) v^(1/10), beta = (3/2) A (rho / m_eff)^(2/5)
/// with rho and m_eff of the pair (Eqs. (3), (8) of MP2011). Integrated in 1D with 3200
/// steps per contact duration (Hertz, a bound above the damped one); at that step the
/// isolated contacts of equal spheres are within 3e-6 of the law (soft_contact.rs), and
/// the error must fall with the step (order >= 1 between 800 and 3200 steps).
#[test]
fn unlike_spheres_follow_the_exact_law_of_their_pair() {
    let (first, second) = ((0.5, 1.0), (0.8, 3.0));
    let effective_mass = 0.75;
    for a in [1e-3, 0.05, 0.5] {
        let material = ViscoelasticMaterial::new(YOUNG, POISSON, a).unwrap();
        let rho = material.elastic_constant(first.0, second.0);
        for v in [0.1f64, 1.0, 10.0] {
            let vstar = material.beta(first.0, second.0, first.1, second.1).sqrt() * v.powf(0.1);
            let exact = solve(vstar, Criterion::Improved).unwrap().eps;
            let duration = gas::soft::contact::hertz_duration(rho, effective_mass, v);
            let error = |steps: f64| {
                let dt = duration / steps;
                isolated_contact_eps(material, first, second, v, dt, 0.5).unwrap() - exact
            };
            let (coarse, fine) = (error(800.0).abs(), error(3200.0).abs());
            assert!(
                fine < 3e-6 && (fine <= coarse / 4.0 || fine < 1e-9),
                "A = {a}, v = {v} (v* = {vstar}): {coarse:e} at 800, {fine:e} at 3200 steps"
            );
        }
    }
}

fn mixture<const D: usize>(n: usize, phi: f64) -> System<D> {
    let species = [
        Species {
            diameter: 1.0,
            mass: 1.0,
            fraction: 0.5,
        },
        Species {
            diameter: 1.5,
            mass: 3.0,
            fraction: 0.5,
        },
    ];
    polydisperse::<D>(n, phi, &species, 1.0, 5).unwrap()
}

fn momentum<const D: usize>(s: &System<D>) -> [f64; D] {
    std::array::from_fn(|k| (0..s.len()).map(|i| s.masses[i] * s.velocities[i][k]).sum())
}

fn kinetic<const D: usize>(s: &System<D>) -> f64 {
    (0..s.len())
        .map(|i| 0.5 * s.masses[i] * s.velocities[i].iter().map(|v| v * v).sum::<f64>())
        .sum()
}

/// Largest |kinetic + elastic + lost - initial| over the run, relative to the energy lost at
/// the end, and the largest |momentum| per particle (in units of sqrt(m T)).
fn run<const D: usize>(system: System<D>, steps_per_contact: f64, end: f64) -> (f64, f64) {
    let material = ViscoelasticMaterial::new(YOUNG, POISSON, 0.05).unwrap();
    let n = system.len() as f64;
    let options = SoftSphereOptions {
        steps_per_contact,
        ..Default::default()
    };
    let mut engine = SoftSphere::new(system, material, options).unwrap();
    let initial = kinetic(engine.system()) + engine.elastic_energy();
    let (mut worst_energy, mut worst_momentum) = (0.0f64, 0.0f64);
    for k in 1..=20 {
        engine.run_until(end * k as f64 / 20.0);
        let lost = engine.counters().energy_lost;
        let balance = kinetic(engine.system()) + engine.elastic_energy() + lost - initial;
        worst_energy = worst_energy.max(balance.abs());
        for p in momentum(engine.system()) {
            worst_momentum = worst_momentum.max(p.abs() / n);
        }
    }
    let lost = engine.counters().energy_lost;
    assert!(
        engine.counters().collisions as f64 > 2.0 * n && lost > 0.1 * initial,
        "the mixture collides and cools: {:?}",
        engine.counters()
    );
    (worst_energy / lost, worst_momentum)
}

/// A binary mixture (diameters 1 and 1.5, masses 1 and 3) in 1D, 2D and 3D: the total
/// momentum stays zero to round-off (forces come in pairs), and the energy books balance
/// to the integrator's accuracy: below 1e-3 of the energy lost at the default 50 steps per
/// contact, and falling at least 2.4 times (order 1.5, as for one contact) when the step
/// is halved.
#[test]
fn mixtures_conserve_momentum_and_balance_energy() {
    fn check<const D: usize>(n: usize, phi: f64, end: f64) {
        let (coarse, p) = run(mixture::<D>(n, phi), 50.0, end);
        let (fine, _) = run(mixture::<D>(n, phi), 100.0, end);
        println!("{D}D: energy imbalance {coarse:e} (50 steps), {fine:e} (100); momentum {p:e}");
        assert!(p < 1e-12, "{D}D momentum per particle {p:e}");
        assert!(
            coarse < 1e-3 && fine < coarse / 2.4,
            "{D}D: {coarse:e} at 50, {fine:e} at 100 steps per contact"
        );
    }
    check::<1>(100, 0.2, 100.0);
    check::<2>(300, 0.2, 20.0);
    check::<3>(300, 0.2, 10.0);
}
