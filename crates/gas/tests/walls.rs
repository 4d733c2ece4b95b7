//! The event-driven engine in a container: walls against conservation laws, equilibrium
//! statistical mechanics and the Carnahan–Starling equation of state.

use gas::init::monodisperse_reporting;
use gas::observe::{kinetic_energy, temperature};
use gas::walls::{Side, Wall, WallKind, Walls};
use gas::{Checkpoint, Engine, EventDriven};
use restitution::Constant;

fn wall(axis: usize, side: Side, kind: WallKind) -> Wall {
    Wall { axis, side, kind }
}

/// A gas of `n` unit spheres at packing fraction `phi` (of the whole box) with walls
/// `kinds(axis, side)` on both sides of the axes `closed`.
fn boxed<const D: usize>(
    n: usize,
    phi: f64,
    eps: f64,
    closed: &[usize],
    kind: impl Fn(usize, Side) -> WallKind,
    seed: u64,
) -> EventDriven<D> {
    let shut: [bool; D] = std::array::from_fn(|k| closed.contains(&k));
    let (system, _) = monodisperse_reporting::<D>(n, phi, 1.0, 1.0, 1.0, seed, shut).unwrap();
    let mut engine = EventDriven::new(system, Box::new(Constant::new(eps).unwrap())).unwrap();
    let walls = closed
        .iter()
        .flat_map(|&k| [Side::Low, Side::High].map(|s| wall(k, s, kind(k, s))))
        .collect();
    engine
        .set_walls(Some(Walls::new(walls, seed).unwrap()))
        .unwrap();
    engine
}

/// Every sphere inside the walls (its centre at least its radius from each, to round-off).
fn assert_inside<const D: usize>(engine: &mut EventDriven<D>, closed: &[usize]) {
    let s = engine.system().clone();
    for (i, x) in s.positions.iter().enumerate() {
        for &k in closed {
            let r = s.radii[i];
            assert!(
                x[k] >= r - 1e-9 && x[k] <= s.sides[k] - r + 1e-9,
                "sphere {i} at {} on axis {k} of a box of {}",
                x[k],
                s.sides[k]
            );
        }
    }
}

/// Elastic spheres between elastic walls on every axis: the energy is conserved to
/// round-off (a wall contact reverses one component), no sphere leaves the box, no pair
/// collision is missed, and no pair collides through a wall (the minimum image is off on
/// closed axes: a collision "through" a wall would conserve energy too, but leave spheres
/// outside, which `assert_inside` catches).
#[test]
fn elastic_walls_conserve_energy_and_hold_the_gas() {
    for (dimension_closed, phi) in [(&[0usize, 1, 2][..], 0.05), (&[2usize][..], 0.3)] {
        let mut e = boxed::<3>(500, phi, 1.0, dimension_closed, |_, _| WallKind::Elastic, 3);
        let e0 = kinetic_energy(e.system());
        for _ in 0..10 {
            e.run_collisions(5_000);
            assert_inside(&mut e, dimension_closed);
        }
        assert!(e.missed_collision().is_none());
        let drift = (kinetic_energy(e.system()) - e0).abs() / e0;
        assert!(drift < 1e-12, "energy drift {drift}");
        let walls = e.walls().unwrap();
        assert!(walls.tallies().iter().all(|t| t.collisions > 100));
        assert!(walls.tallies().iter().all(|t| t.energy == 0.0));
    }
}

/// Elastic spheres between restitution walls (eps_w = 0.8): the gas cools only at the
/// walls, so the kinetic energy lost equals minus the energy the walls gave, to round-off
/// (the bookkeeping of `Walls::bounce` against the engine's velocities).
#[test]
fn restitution_walls_account_for_the_energy_lost() {
    let mut e = boxed::<2>(
        400,
        0.2,
        1.0,
        &[1],
        |_, _| WallKind::Restitution(Box::new(Constant::new(0.8).unwrap())),
        5,
    );
    let e0 = kinetic_energy(e.system());
    e.run_collisions(20_000);
    let given: f64 = e.walls().unwrap().tallies().iter().map(|t| t.energy).sum();
    let change = kinetic_energy(e.system()) - e0;
    assert!(given < -0.05 * e0, "the walls took {given} of {e0}");
    assert!(
        (change - given).abs() < 1e-10 * e0,
        "kinetic energy changed by {change}, walls gave {given}"
    );
    assert_inside(&mut e, &[1]);
}

/// Elastic spheres between two thermal walls at T_w = 2 (started at T = 1): Maxwell's
/// diffuse wall obeys detailed balance with the Maxwellian at T_w, so the gas relaxes to
/// the equilibrium at T_w exactly. The temperature over the second half, averaged over
/// samples (their spread gives the error; samples 200 collisions per particle apart are
/// nearly independent for T, tolerance 5 standard errors), equals T_w; the walls' net
/// energy flux in that half is zero within its fluctuation.
#[test]
fn thermal_walls_bring_the_gas_to_their_temperature() {
    let t_wall = 2.0;
    let mut e = boxed::<2>(
        300,
        0.1,
        1.0,
        &[0],
        |_, _| WallKind::Thermal {
            temperature: t_wall,
        },
        9,
    );
    // Relaxation: the walls reach the gas through ~L / (mean free path) ~ 10 collisions
    // across; 2000 collisions per particle is ample.
    e.run_collisions(300_000);
    let mut samples = Vec::new();
    for _ in 0..60 {
        e.run_collisions(15_000);
        samples.push(temperature(e.system()));
    }
    let n = samples.len() as f64;
    let mean = samples.iter().sum::<f64>() / n;
    let var = samples.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let error = (var / n).sqrt();
    eprintln!("T = {mean:.4} +- {error:.4} between walls at {t_wall}");
    assert!((mean - t_wall).abs() < 5.0 * error, "{mean} +- {error}");
    assert_inside(&mut e, &[0]);
}

/// A check-point taken mid-run between thermal walls (whose random stream is part of the
/// state) and restored continues bit for bit: positions, velocities and wall tallies.
#[test]
fn walls_resume_bit_for_bit() {
    let kind = |_: usize, s: Side| match s {
        Side::Low => WallKind::Thermal { temperature: 1.5 },
        Side::High => WallKind::Restitution(Box::new(Constant::new(0.9).unwrap())),
    };
    let mut a = boxed::<3>(300, 0.1, 0.95, &[2], kind, 13);
    a.run_collisions(5_000);
    let state = a.save();
    let text = serde_json::to_string(&state).unwrap();
    let mut b = EventDriven::<3>::restore(
        serde_json::from_str(&text).unwrap(),
        Box::new(Constant::new(0.95).unwrap()),
    )
    .unwrap();
    let walls = [Side::Low, Side::High].map(|s| wall(2, s, kind(2, s)));
    b.set_walls(Some(Walls::new(walls.into(), 13).unwrap()))
        .unwrap();
    a.run_collisions(5_000);
    b.run_collisions(5_000);
    assert_eq!(a.system().positions, b.system().positions);
    assert_eq!(a.system().velocities, b.system().velocities);
    assert_eq!(a.walls().unwrap().tallies(), b.walls().unwrap().tallies());
    assert_eq!(a.collision_counts(), b.collision_counts());
}

/// A state saved with walls refuses to run without them.
#[test]
fn a_state_with_walls_needs_its_walls() {
    let mut a = boxed::<2>(100, 0.1, 1.0, &[0], |_, _| WallKind::Elastic, 1);
    a.run_collisions(100);
    let mut b = EventDriven::<2>::restore(a.save(), Box::new(Constant::new(1.0).unwrap())).unwrap();
    assert!(b.set_walls(None).is_err());
}

/// Walls named badly are refused: one side of an axis, a side twice, an axis beyond the
/// dimension, a cold thermal wall.
#[test]
fn bad_walls_are_refused() {
    let w = |axis, side| wall(axis, side, WallKind::Elastic);
    assert!(Walls::<2>::new(vec![w(0, Side::Low)], 1).is_err());
    assert!(Walls::<2>::new(vec![w(0, Side::Low), w(0, Side::Low), w(0, Side::High)], 1).is_err());
    assert!(Walls::<2>::new(vec![w(2, Side::Low), w(2, Side::High)], 1).is_err());
    let cold = |side| wall(0, side, WallKind::Thermal { temperature: 0.0 });
    assert!(Walls::<2>::new(vec![cold(Side::Low), cold(Side::High)], 1).is_err());
}

/// Hard spheres between elastic walls: by the contact theorem the wall's pressure is the
/// bulk pressure, P = n T Z(phi) with Z of Carnahan–Starling (its error is below 0.3 % at
/// phi = 0.25) at the bulk density n, measured in the middle half of the box (away from
/// the layering at the walls). P from the wall momentum per unit time and area over ten
/// blocks (their spread gives the error; tolerance 4 standard errors plus CS's 0.3 %).
#[test]
fn wall_pressure_follows_carnahan_starling() {
    let mut e = boxed::<3>(2000, 0.25, 1.0, &[2], |_, _| WallKind::Elastic, 21);
    e.run_collisions(200_000);
    let (length, t) = (e.system().sides[0], temperature(e.system()));
    let area = length * length;
    let mut pressures = Vec::new();
    let mut middle = 0usize;
    let mut looks = 0usize;
    for _ in 0..10 {
        let (t0, m0): (f64, f64) = (e.time(), momentum(&e));
        for _ in 0..20 {
            e.run_collisions(4_000);
            let s = e.system();
            middle += s
                .positions
                .iter()
                .filter(|x| (x[2] - 0.5 * length).abs() < 0.25 * length)
                .count();
            looks += 1;
        }
        pressures.push((momentum(&e) - m0) / (2.0 * area * (e.time() - t0)));
    }
    let n = pressures.len() as f64;
    let p = pressures.iter().sum::<f64>() / n;
    let error = (pressures.iter().map(|x| (x - p).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
    let density = middle as f64 / looks as f64 / (0.5 * length * area);
    let phi = density * std::f64::consts::PI / 6.0;
    let z = (1.0 + phi + phi * phi - phi.powi(3)) / (1.0 - phi).powi(3);
    let expected = density * t * z;
    eprintln!("wall pressure {p:.4} +- {error:.4}; CS at the bulk phi = {phi:.4}: {expected:.4}");
    assert!(
        (p - expected).abs() < 4.0 * error + 0.003 * expected,
        "{p} +- {error} vs {expected}"
    );
}

/// The normal momentum both walls of the engine have taken so far.
fn momentum<const D: usize>(e: &EventDriven<D>) -> f64 {
    e.walls()
        .unwrap()
        .tallies()
        .iter()
        .map(|t| t.momentum)
        .sum()
}
