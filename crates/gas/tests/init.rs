//! Initial states: the monodisperse initializer is pinned bit for bit, the polydisperse one
//! gives the requested packing fraction, temperature, species counts, zero momentum and no
//! overlaps.

use gas::init::{
    monodisperse, monodisperse_reporting, polydisperse, polydisperse_reporting, species_counts,
    Species,
};
use gas::observe::{mean_velocity, temperature};
use gas::system::dot;
use gas::System;

/// FNV-1a over the bits of the whole state.
fn hash<const D: usize>(s: &System<D>) -> u64 {
    let mut h: u64 = 0xcbf29ce484222325;
    let mut eat = |x: f64| {
        h ^= x.to_bits();
        h = h.wrapping_mul(0x100000001b3);
    };
    // A cube as one side (the hashes of the states before boxes had sides of their own).
    if s.is_cubic() {
        eat(s.sides[0]);
    } else {
        s.sides.iter().for_each(|&l| eat(l));
    }
    for x in s.positions.iter().chain(&s.velocities).flatten() {
        eat(*x);
    }
    for x in s.radii.iter().chain(&s.masses) {
        eat(*x);
    }
    h
}

/// Random sequential addition states as produced before mixtures existed (the melted dense
/// states depend on the engine's round-off and are not pinned).
#[test]
fn monodisperse_states_are_unchanged() {
    let a = monodisperse::<3>(1000, 0.05, 1.0, 1.0, 1.0, 1).unwrap();
    let b = monodisperse::<2>(500, 0.2, 1.3, 2.0, 0.7, 2).unwrap();
    let c = monodisperse::<1>(100, 0.1, 1.0, 3.0, 1.0, 3).unwrap();
    let d = monodisperse::<3>(500, 0.3, 1.0, 1.0, 1.0, 4).unwrap();
    assert_eq!(hash(&a), 0x15d9e040174cec5);
    assert_eq!(hash(&b), 0x287600bc54c31d1e);
    assert_eq!(hash(&c), 0x47d7f7008d439f84);
    assert_eq!(hash(&d), 0x9ef3b4c590ee60ae);
}

fn binary() -> [Species; 2] {
    [
        Species {
            diameter: 1.0,
            mass: 1.0,
            fraction: 0.5,
        },
        Species {
            diameter: 1.4,
            mass: 2.744,
            fraction: 0.5,
        },
    ]
}

/// Everything a mixture's initial state must satisfy.
fn check_mixture<const D: usize>(s: &System<D>, phi: f64, t: f64, species: &[Species]) {
    let n = s.len();
    assert!(
        (s.packing_fraction() - phi).abs() < 1e-12 * phi,
        "{}",
        s.packing_fraction()
    );
    assert!((temperature(s) - t).abs() < 1e-12 * t, "{}", temperature(s));
    let (_, momentum) = mean_velocity(s);
    let scale: f64 = s
        .velocities
        .iter()
        .zip(&s.masses)
        .map(|(v, m)| m * dot(v, v).sqrt())
        .sum();
    assert!(
        momentum.iter().all(|p| p.abs() < 1e-13 * scale),
        "{momentum:?}"
    );
    let counts = species_counts(n, species).unwrap();
    for (k, x) in species.iter().enumerate() {
        let members: Vec<usize> = (0..n)
            .filter(|&i| s.radii[i] == 0.5 * x.diameter && s.masses[i] == x.mass)
            .collect();
        assert_eq!(members.len(), counts[k], "species {k}");
        // Each species near the requested temperature (500+ particles: a few per cent).
        let tk = members
            .iter()
            .map(|&i| s.masses[i] * dot(&s.velocities[i], &s.velocities[i]))
            .sum::<f64>()
            / (members.len() * D) as f64;
        assert!((tk / t - 1.0).abs() < 0.15, "species {k}: T = {tk}");
    }
    for i in 0..n {
        assert!(s.positions[i]
            .iter()
            .all(|&x| (0.0..s.sides[0]).contains(&x)));
        for j in i + 1..n {
            let r = s.separation(&s.positions[i], &s.positions[j]);
            let sigma = s.radii[i] + s.radii[j];
            assert!(
                dot(&r, &r) >= sigma * sigma * (1.0 - 1e-12),
                "{i} and {j} overlap"
            );
        }
    }
}

#[test]
fn binary_mixture_by_random_addition() {
    let species = binary();
    let s = polydisperse::<3>(1000, 0.2, &species, 1.5, 11).unwrap();
    check_mixture(&s, 0.2, 1.5, &species);
    // The species are mixed in memory (ordered in space, not in blocks).
    let big_in_first_half = s.radii[..500].iter().filter(|&&r| r == 0.7).count();
    assert!(
        (150..350).contains(&big_in_first_half),
        "{big_in_first_half}"
    );
    assert_eq!(
        hash(&s),
        hash(&polydisperse::<3>(1000, 0.2, &species, 1.5, 11).unwrap())
    );
    assert_ne!(
        hash(&s),
        hash(&polydisperse::<3>(1000, 0.2, &species, 1.5, 12).unwrap())
    );
}

#[test]
fn dense_binary_mixture_from_a_melted_lattice() {
    let species = binary();
    let s = polydisperse::<3>(1000, 0.35, &species, 1.0, 5).unwrap();
    check_mixture(&s, 0.35, 1.0, &species);
    // At 0.4 the simple lattice of the largest diameter no longer fits: the spheres grow.
    let (s, report) = polydisperse_reporting::<3>(1000, 0.4, &species, 1.0, 5, [false; 3]).unwrap();
    check_mixture(&s, 0.4, 1.0, &species);
    assert!(report.is_some());
}

/// Dense starts up to the limits of the initializer (0.60 in 3D, 0.80 in 2D, a binary
/// mixture at 0.60): the grown spheres do not overlap (all pairs checked), the state has
/// the temperature, zero momentum and the species counts asked for, the event-driven engine
/// takes it (its own overlap check) and runs it without missing a collision
/// (`EventDriven::missed_collision`, all pairs), and the growth's cost is reported.
#[test]
fn dense_starts_grow_the_spheres() {
    let one = [Species {
        diameter: 1.0,
        mass: 1.0,
        fraction: 1.0,
    }];
    let species = binary();
    let (s, r) = monodisperse_reporting::<3>(1500, 0.6, 1.0, 1.0, 1.0, 3, [false; 3]).unwrap();
    check_mixture(&s, 0.6, 1.0, &one);
    check_grown("3D, phi = 0.60", 0.6, r, s);
    let (s, r) = monodisperse_reporting::<2>(1500, 0.8, 1.0, 1.0, 1.0, 4, [false; 2]).unwrap();
    check_mixture(&s, 0.8, 1.0, &one);
    check_grown("2D, phi = 0.80", 0.8, r, s);
    let (s, r) = polydisperse_reporting::<3>(1500, 0.6, &species, 1.0, 5, [false; 3]).unwrap();
    check_mixture(&s, 0.6, 1.0, &species);
    check_grown("3D binary, phi = 0.60", 0.6, r, s);
}

/// The event-driven engine takes a grown state (its own overlap check) and runs 3000
/// collisions without missing one; the growth's report is there and consistent.
fn check_grown<const D: usize>(
    name: &str,
    phi: f64,
    report: Option<gas::init::GrowthReport>,
    s: System<D>,
) {
    use gas::{Engine, EventDriven};
    let mut e = EventDriven::new(s, law()).unwrap();
    e.run_collisions(3000);
    assert_eq!(e.missed_collision(), None, "{name}");
    let report = report.expect("a grown start");
    eprintln!("{name}: {report:?}; 3000 collisions in time {}", e.time());
    assert!(report.collisions > 0 && report.events >= report.collisions);
    assert!((report.start_fraction - 0.3).abs() < 1e-12 && phi > report.start_fraction);
}

/// A grown start is the equilibrium hard-sphere fluid: at phi = 0.48 (a stable fluid, below
/// freezing at 0.494) an elastic gas of 2000 spheres, after 20 collisions per particle, has
/// the Enskog collision frequency and the pressure Z = 1 + 4 phi g2 of Carnahan–Starling's
/// contact value (oracle: `gas::theory`, independent of the growth). Tolerance 1.5 %:
/// Carnahan–Starling's error at 0.48 (< 0.5 % against MD equations of state, Kolafa et al.
/// 2004), the finite size (O(1/N)) and the statistics of 2e5 collisions (< 0.3 % at 3 sigma
/// for the rate; the virial's fluctuations a few times larger).
#[test]
fn grown_starts_are_the_equilibrium_fluid() {
    use gas::{Engine, EventDriven};
    let (n, phi) = (2000, 0.48);
    let (s, report) = monodisperse_reporting::<3>(n, phi, 1.0, 1.0, 1.0, 11, [false; 3]).unwrap();
    assert!(report.is_some());
    let volume = s.volume();
    let mut e = EventDriven::new(s, law()).unwrap();
    e.run_collisions(20 * n as u64 / 2);
    let (t0, c0) = (e.time(), e.counters());
    e.run_collisions(200 * n as u64 / 2);
    let (t1, c1) = (e.time(), e.counters());
    let dt = t1 - t0;
    let rate = 2.0 * (c1.collisions - c0.collisions) as f64 / (n as f64 * dt);
    let theory = gas::theory::collision_frequency::<3>(n as f64 / volume, 1.0, 1.0, 1.0, phi);
    let pressure = gas::observe::pressure::<3>(n, volume, 1.0, 1.0, c1.virial - c0.virial, dt);
    let z = pressure * volume / n as f64;
    let z_theory = 1.0 + 4.0 * phi * gas::theory::contact_value::<3>(phi);
    eprintln!("rate {rate} vs {theory}; Z {z} vs {z_theory}");
    assert!(
        (rate / theory - 1.0).abs() < 0.015,
        "rate {rate} vs {theory}"
    );
    assert!((z / z_theory - 1.0).abs() < 0.015, "Z {z} vs {z_theory}");
}

fn law() -> Box<dyn restitution::Restitution> {
    Box::new(restitution::Constant::new(1.0).unwrap())
}

#[test]
fn three_species_in_two_and_one_dimensions() {
    let species = [
        Species {
            diameter: 1.0,
            mass: 1.0,
            fraction: 3.0,
        },
        Species {
            diameter: 0.5,
            mass: 0.25,
            fraction: 2.0,
        },
        Species {
            diameter: 2.0,
            mass: 4.0,
            fraction: 1.0,
        },
    ];
    assert_eq!(species_counts(1200, &species).unwrap(), vec![600, 400, 200]);
    let s = polydisperse::<2>(3000, 0.25, &species, 2.0, 3).unwrap();
    check_mixture(&s, 0.25, 2.0, &species);
    let s = polydisperse::<1>(3000, 0.5, &species, 0.5, 4).unwrap();
    check_mixture(&s, 0.5, 0.5, &species);
}

#[test]
fn species_counts_sum_to_n() {
    let third = Species {
        diameter: 1.0,
        mass: 1.0,
        fraction: 1.0,
    };
    assert_eq!(species_counts(10, &[third; 3]).unwrap(), vec![4, 3, 3]);
    let mut uneven = [third; 3];
    uneven[1].fraction = 0.7;
    uneven[2].fraction = 0.3;
    assert_eq!(species_counts(7, &uneven).unwrap(), vec![4, 2, 1]);
    assert_eq!(species_counts(5, &[third]).unwrap(), vec![5]);
    let mut rare = [third; 2];
    rare[1].fraction = 1e-3;
    let error = species_counts(100, &rare).unwrap_err().to_string();
    assert!(error.contains("species[1].fraction"), "{error}");
    rare[1].fraction = 0.0;
    assert!(species_counts(100, &rare).is_err());
    assert!(species_counts(100, &[]).is_err());
}

#[test]
fn bad_species_are_rejected() {
    let mut species = binary();
    species[1].mass = -1.0;
    let error = polydisperse::<3>(100, 0.1, &species, 1.0, 1)
        .unwrap_err()
        .to_string();
    assert!(error.contains("species[1].mass"), "{error}");
    let mut species = binary();
    species[0].diameter = f64::NAN;
    let error = polydisperse::<3>(100, 0.1, &species, 1.0, 1)
        .unwrap_err()
        .to_string();
    assert!(error.contains("species[0].diameter"), "{error}");
    // Above the 3D limit of a grown start (0.6) a mixture is refused naming the key.
    let error = polydisperse::<3>(100, 0.65, &binary(), 1.0, 1)
        .unwrap_err()
        .to_string();
    assert!(error.contains("packing_fraction"), "{error}");
}
