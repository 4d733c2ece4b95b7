//! Vibrating walls in the event-driven engine: contacts against closed forms (a sawtooth
//! wall moves at constant speed), grazing and near-miss flights against a sine wall, the
//! energy balance of a vibrated gas (what the gas gains is what the walls gave), and
//! spheres never behind a moving wall.

use gas::init::monodisperse_reporting;
use gas::observe::kinetic_energy;
use gas::system::System;
use gas::walls::{Motion, Side, Wall, WallKind, Walls, Waveform};
use gas::{Engine, EventDriven};
use restitution::Constant;

fn vibrating(amplitude: f64, frequency: f64, waveform: Waveform, eps: f64) -> WallKind {
    WallKind::Vibrating {
        law: Box::new(Constant::new(eps).unwrap()),
        motion: Motion {
            amplitude,
            frequency,
            waveform,
        },
    }
}

/// One sphere of radius 0.5 in a 2D box of side 10, axis y closed by `floor` and an
/// elastic ceiling.
fn one_sphere(y: f64, v: [f64; 2], floor: WallKind, g: f64) -> EventDriven<2> {
    let system = System::<2> {
        sides: [10.0; 2],
        positions: vec![[5.0, y]],
        velocities: vec![v],
        radii: vec![0.5],
        masses: vec![1.0],
    };
    let mut e = EventDriven::new(system, Box::new(Constant::new(1.0).unwrap())).unwrap();
    let walls = vec![
        Wall {
            axis: 1,
            side: Side::Low,
            kind: floor,
        },
        Wall {
            axis: 1,
            side: Side::High,
            kind: WallKind::Elastic,
        },
    ];
    e.set_walls(Some(Walls::new(walls, 1).unwrap())).unwrap();
    if g != 0.0 {
        e.set_gravity(Some([0.0, -g]), 0.0).unwrap();
    }
    e
}

/// Oracle: a sawtooth floor rises at 2 A f; a sphere falling at speed w from y0 meets it
/// when y0 − w s − r = 2 A f s, s* = (y0 − r) / (w + 2 A f), and leaves elastically at
/// 2 (2 A f) + w in the box (reflection in the wall's frame).
#[test]
fn a_sawtooth_wall_is_met_at_the_closed_form_time() {
    let (a, f, w, y0) = (0.4, 0.1, 1.5, 3.0);
    let mut e = one_sphere(y0, [0.0, -w], vibrating(a, f, Waveform::Sawtooth, 1.0), 0.0);
    let speed = 2.0 * a * f;
    let contact = (y0 - 0.5) / (w + speed);
    e.run_until(contact - 1e-9);
    assert_eq!(e.walls().unwrap().tallies()[0].collisions, 0);
    e.run_until(contact + 1e-9);
    assert_eq!(e.walls().unwrap().tallies()[0].collisions, 1);
    let s = e.system();
    assert!(
        (s.velocities[0][1] - (2.0 * speed + w)).abs() < 1e-12,
        "{:?}",
        s.velocities[0]
    );
    // The energy the wall gave: (v'^2 - v^2) / 2.
    let given = e.walls().unwrap().tallies()[0].energy;
    assert!((given - 0.5 * ((2.0 * speed + w).powi(2) - w * w)).abs() < 1e-12);
}

/// Oracle: the sphere is never behind the wall. A sphere at rest at the top of a sine
/// wall's sweep (y = r + 2A) is touched with zero relative speed at t = 1 / (2 f) (a
/// grazing contact, harmless); one 1e-9 lower is hit (the wall catches it near the top
/// of its stroke, at a relative speed ~ sqrt(2 A_accel 1e-9)) and must leave above the
/// wall; one 1e-9 higher is never touched. Checked on a fine time grid.
#[test]
fn grazing_and_near_misses_against_a_sine_wall() {
    let (a, f) = (0.2, 0.5);
    let motion = Motion {
        amplitude: a,
        frequency: f,
        waveform: Waveform::Sine,
    };
    for (offset, touched) in [(-1e-9, true), (1e-9, false), (-1e-3, true)] {
        let y0 = 0.5 + 2.0 * a + offset;
        let mut e = one_sphere(y0, [0.0, 0.0], vibrating(a, f, Waveform::Sine, 1.0), 0.0);
        let mut t = 0.0;
        while t < 3.0 / f {
            t += 1e-3;
            e.run_until(t);
            let y = e.system().positions[0][1];
            assert!(
                y >= 0.5 + motion.displacement(t) - 1e-9,
                "offset {offset}, t {t}: y {y}"
            );
        }
        let contacts = e.walls().unwrap().tallies()[0].collisions;
        assert_eq!(
            contacts > 0,
            touched,
            "offset {offset}: {contacts} contacts"
        );
    }
}

/// Elastic spheres between a vibrating floor (each waveform) and an elastic ceiling, no
/// gravity: the gas's kinetic energy changes by exactly what the walls gave (1e-10,
/// round-off of the sums), no sphere is ever behind the moving floor, no pair collision
/// is missed. Then in gravity, with kinetic plus potential energy.
#[test]
fn a_vibrated_gas_gains_what_the_walls_give() {
    for (waveform, g) in [
        (Waveform::Sine, 0.0),
        (Waveform::Triangle, 0.0),
        (Waveform::Sawtooth, 0.0),
        (Waveform::Sine, 0.5),
    ] {
        let (system, _) =
            monodisperse_reporting::<3>(400, 0.1, 1.0, 1.0, 1.0, 2, [false, false, true]).unwrap();
        let mut e = EventDriven::new(system, Box::new(Constant::new(1.0).unwrap())).unwrap();
        let (a, f) = (0.3, 0.7);
        let walls = vec![
            Wall {
                axis: 2,
                side: Side::Low,
                kind: vibrating(a, f, waveform, 0.9),
            },
            Wall {
                axis: 2,
                side: Side::High,
                kind: WallKind::Elastic,
            },
        ];
        e.set_walls(Some(Walls::new(walls, 2).unwrap())).unwrap();
        if g != 0.0 {
            e.set_gravity(Some([0.0, 0.0, -g]), 0.0).unwrap();
        }
        let energy = |e: &mut EventDriven<3>| {
            let s = e.system();
            let potential: f64 = s.positions.iter().map(|x| g * x[2]).sum();
            kinetic_energy(s) + potential
        };
        let e0 = energy(&mut e);
        let motion = e.walls().unwrap().motion(0).unwrap();
        for _ in 0..20 {
            e.run_collisions(2_000);
            let t = e.time();
            let s = e.system();
            for x in &s.positions {
                assert!(
                    x[2] >= 0.5 + motion.displacement(t) - 1e-9,
                    "{waveform:?}: {x:?} at {t}"
                );
            }
        }
        assert!(e.missed_collision().is_none());
        let given: f64 = e.walls().unwrap().tallies().iter().map(|t| t.energy).sum();
        let change = energy(&mut e) - e0;
        eprintln!("{waveform:?}, g {g}: gained {change}, walls gave {given}");
        assert!((change - given).abs() < 1e-10 * e0, "{change} vs {given}");
        assert!(e.walls().unwrap().tallies()[0].collisions > 100);
    }
}

/// A vibrating wall whose sweep reaches the opposite wall is refused, naming its
/// amplitude.
#[test]
fn a_sweep_across_the_box_is_refused() {
    let system = System::<2> {
        sides: [4.0; 2],
        positions: vec![[2.0, 2.0]],
        velocities: vec![[0.0, 1.0]],
        radii: vec![0.5],
        masses: vec![1.0],
    };
    let mut e = EventDriven::new(system, Box::new(Constant::new(1.0).unwrap())).unwrap();
    let walls = vec![
        Wall {
            axis: 1,
            side: Side::Low,
            kind: vibrating(0.8, 1.0, Waveform::Sine, 1.0),
        },
        Wall {
            axis: 1,
            side: Side::High,
            kind: vibrating(0.8, 1.0, Waveform::Sine, 1.0),
        },
    ];
    let error = e
        .set_walls(Some(Walls::new(walls, 2).unwrap()))
        .unwrap_err();
    assert!(error.to_string().contains("amplitude"), "{error}");
}
