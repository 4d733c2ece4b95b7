//! Walls and gravity in soft-sphere MD: a wall contact against the exact viscoelastic
//! coefficient of restitution of a sphere on a half-space, a bed resting on its floor
//! against its weight, and check-points.

use gas::soft::contact::ViscoelasticMaterial;
use gas::system::System;
use gas::walls::{Side, Wall, WallKind, Walls};
use gas::{Checkpoint, Engine, SoftSphere, SoftSphereOptions};
use restitution::exact::{solve, Criterion};
use restitution::Constant;

fn walls_on(axis: usize, low: WallKind, high: WallKind) -> Walls<3> {
    Walls::new(
        vec![
            Wall {
                axis,
                side: Side::Low,
                kind: low,
            },
            Wall {
                axis,
                side: Side::High,
                kind: high,
            },
        ],
        1,
    )
    .unwrap()
}

fn damped() -> WallKind {
    // The soft engine takes the material's contact for a restitution wall.
    WallKind::Restitution(Box::new(Constant::new(1.0).unwrap()))
}

/// Oracle: a sphere (R = 0.5, m = 1) hitting a wall of its own material head-on leaves
/// with eps(v) of the viscoelastic law at β_w = (3/2) A (ρ_w / m)^{2/5}, ρ_w = 2 Y √R /
/// (3 (1 − ν²)) (`restitution::exact`, improved criterion), to the integrator's error:
/// 1e-3 at 400 steps per contact (measured: 3e-5).
#[test]
fn a_wall_contact_has_the_viscoelastic_restitution() {
    let material = ViscoelasticMaterial::new(1e5, 0.3, 0.005).unwrap();
    let rho = 2.0 * 1e5 * 0.5f64.sqrt() / (3.0 * (1.0 - 0.09));
    let beta = 1.5 * 0.005 * rho.powf(0.4);
    for v in [0.5, 2.0] {
        // A second sphere flies far from the first and from the walls (it gives the gas
        // the temperature the engine's accuracy probe needs).
        let system = System::<3> {
            sides: [10.0; 3],
            positions: vec![[5.0, 5.0, 0.52], [2.0, 2.0, 5.0]],
            velocities: vec![[0.0, 0.0, -v], [v, 0.0, 0.0]],
            radii: vec![0.5, 0.5],
            masses: vec![1.0, 1.0],
        };
        let duration = gas::soft::contact::hertz_duration(rho, 1.0, v);
        let options = SoftSphereOptions {
            time_step: Some(duration / 400.0),
            ..Default::default()
        };
        let mut e = SoftSphere::new(system, material, options).unwrap();
        e.set_walls(Some(walls_on(2, damped(), WallKind::Elastic)))
            .unwrap();
        e.run_until(0.04 / v + 3.0 * duration);
        let out = e.system().velocities[0][2];
        let exact = solve(beta.sqrt() * v.powf(0.1), Criterion::Improved)
            .unwrap()
            .eps;
        eprintln!("v {v}: eps MD {} exact {exact}", out / v);
        assert!((out / v - exact).abs() < 1e-3, "{} vs {exact}", out / v);
        let tally = e.walls().unwrap().tallies()[0];
        assert_eq!(tally.collisions, 1);
        // The energy the wall gave is what the contact took, to the trapezoid's error.
        let taken = 0.5 * (v * v - out * out);
        assert!(
            (tally.energy + taken).abs() < 1e-3 * taken,
            "{} vs {taken}",
            tally.energy
        );
        // Its impulse: the momentum change.
        assert!((tally.momentum - (v + out)).abs() < 1e-3 * v);
    }
}

/// Oracle: a damped bed at rest on its floor in gravity weighs on it: over a span, the
/// floor takes N m g per unit time (momentum balance, the bed's momentum change tiny once
/// it rests), within 1 % (measured: 1e-12).
#[test]
fn a_resting_bed_weighs_on_its_floor() {
    let material = ViscoelasticMaterial::new(1e5, 0.3, 0.02).unwrap();
    let (system, _) =
        gas::init::monodisperse_reporting::<3>(100, 0.05, 1.0, 1.0, 0.1, 3, [false, false, true])
            .unwrap();
    let mut e = SoftSphere::new(system, material, SoftSphereOptions::default()).unwrap();
    e.set_walls(Some(walls_on(2, damped(), damped()))).unwrap();
    e.set_gravity(Some([0.0, 0.0, -1.0])).unwrap();
    e.run_until(20.0);
    let (t0, p0) = (e.time(), e.walls().unwrap().tallies()[0].momentum);
    e.run_until(30.0);
    let rate = (e.walls().unwrap().tallies()[0].momentum - p0) / (e.time() - t0);
    eprintln!("floor force {rate} vs weight 100");
    assert!((rate / 100.0 - 1.0).abs() < 0.01, "{rate}");
    // Resumes bit for bit.
    let state = e.save();
    let mut resumed = SoftSphere::<3>::restore(state, ()).unwrap();
    resumed
        .set_walls(Some(walls_on(2, damped(), damped())))
        .unwrap();
    resumed.set_gravity(Some([0.0, 0.0, -1.0])).unwrap();
    e.run_until(31.0);
    resumed.run_until(31.0);
    assert_eq!(e.system().clone(), resumed.system().clone());
    assert_eq!(
        e.walls().unwrap().tallies(),
        resumed.walls().unwrap().tallies()
    );
}
