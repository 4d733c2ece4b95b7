//! The event-driven engine with gravity: against free fall, conservation of energy with
//! the potential, the momentum balance of a column (floor minus ceiling pressure = the
//! weight), and a settling bed's bounded work (the resting rule).

use gas::init::monodisperse_reporting;
use gas::observe::kinetic_energy;
use gas::system::System;
use gas::walls::{Side, Wall, WallKind, Walls};
use gas::{Engine, EventDriven};
use restitution::Constant;

/// `n` unit spheres at packing fraction `phi` between walls `floor` (low) and `ceiling`
/// (high) on the last axis, falling with g along it.
fn column<const D: usize>(
    n: usize,
    phi: f64,
    eps: f64,
    floor: WallKind,
    ceiling: WallKind,
    g: f64,
    seed: u64,
) -> EventDriven<D> {
    let shut: [bool; D] = std::array::from_fn(|k| k == D - 1);
    let (system, _) = monodisperse_reporting::<D>(n, phi, 1.0, 1.0, 1.0, seed, shut).unwrap();
    let mut engine = EventDriven::new(system, Box::new(Constant::new(eps).unwrap())).unwrap();
    let walls = vec![
        Wall {
            axis: D - 1,
            side: Side::Low,
            kind: floor,
        },
        Wall {
            axis: D - 1,
            side: Side::High,
            kind: ceiling,
        },
    ];
    engine
        .set_walls(Some(Walls::new(walls, seed).unwrap()))
        .unwrap();
    let gravity: [f64; D] = std::array::from_fn(|k| if k == D - 1 { -g } else { 0.0 });
    engine.set_gravity(Some(gravity), 1e-4).unwrap();
    engine
}

/// Kinetic plus potential energy m g z.
fn energy<const D: usize>(s: &System<D>, g: f64) -> f64 {
    let potential: f64 = (0..s.len())
        .map(|i| s.masses[i] * g * s.positions[i][D - 1])
        .sum();
    kinetic_energy(s) + potential
}

/// Oracle: free fall, z(t) = z0 + v0 t − g t²/2 until the floor at z = r, hit at
/// t* = (v0 + sqrt(v0² + 2 g (z0 − r))) / g, then the elastic bounce. One sphere in a
/// 3D box (the other axes periodic).
#[test]
fn a_sphere_falls_on_its_parabola_and_bounces_on_time() {
    let system = System::<3> {
        sides: [10.0; 3],
        positions: vec![[5.0, 5.0, 7.0]],
        velocities: vec![[0.3, -0.2, 0.5]],
        radii: vec![0.5],
        masses: vec![2.0],
    };
    let mut e = EventDriven::new(system, Box::new(Constant::new(1.0).unwrap())).unwrap();
    let walls = [Side::Low, Side::High].map(|side| Wall {
        axis: 2,
        side,
        kind: WallKind::Elastic,
    });
    e.set_walls(Some(Walls::new(walls.into(), 1).unwrap()))
        .unwrap();
    let g = 1.5;
    e.set_gravity(Some([0.0, 0.0, -g]), 0.0).unwrap();
    let hit = (0.5 + (0.25f64 + 2.0 * g * 6.5).sqrt()) / g;
    for t in [0.3, 1.1, hit - 1e-9] {
        e.run_until(t);
        let s = e.system();
        let z = 7.0 + 0.5 * t - 0.5 * g * t * t;
        assert!(
            (s.positions[0][2] - z).abs() < 1e-13,
            "t {t}: {}",
            s.positions[0][2]
        );
        assert!((s.velocities[0][2] - (0.5 - g * t)).abs() < 1e-13);
        assert!((s.positions[0][0] - (5.0 + 0.3 * t)).abs() < 1e-13);
    }
    assert_eq!(e.walls().unwrap().tallies()[0].collisions, 0);
    e.run_until(hit + 1e-9);
    assert_eq!(e.walls().unwrap().tallies()[0].collisions, 1);
    // After the bounce: up at the impact speed; the apex back at 7 + 0.5^2 / (2 g).
    let apex = hit + (0.25f64 + 2.0 * g * 6.5).sqrt() / g;
    e.run_until(apex);
    let s = e.system();
    let top = 7.0 + 0.25 / (2.0 * g);
    assert!(
        (s.positions[0][2] - top).abs() < 1e-12,
        "{}",
        s.positions[0][2]
    );
    assert!(s.velocities[0][2].abs() < 1e-12);
}

/// Elastic spheres between elastic floor and ceiling in gravity: kinetic plus potential
/// energy is conserved to round-off (positions are kept in the falling frame, which moves
/// with time: the test runs through many such moves), no pair collision is missed, every
/// sphere stays inside.
#[test]
fn an_elastic_column_conserves_its_energy() {
    for (g, phi) in [(0.2, 0.05), (2.0, 0.3)] {
        let mut e = column::<3>(500, phi, 1.0, WallKind::Elastic, WallKind::Elastic, g, 5);
        let e0 = energy(e.system(), g);
        for _ in 0..10 {
            e.run_collisions(10_000);
            let s = e.system();
            for (i, x) in s.positions.iter().enumerate() {
                assert!(
                    x[2] >= 0.5 - 1e-9 && x[2] <= s.sides[2] - 0.5 + 1e-9,
                    "{i}: {x:?}"
                );
            }
        }
        assert!(e.missed_collision().is_none());
        let drift = (energy(e.system(), g) - e0).abs() / e0;
        assert!(drift < 1e-11, "g {g}: energy drift {drift}");
        // Through several moves of the frame (one per sqrt(2 L / g)).
        let horizon = (2.0 * e.system().sides[0] / g).sqrt();
        assert!(e.time() > 3.0 * horizon, "{} of {horizon}", e.time());
    }
}

/// Oracle: the momentum balance of the column. Over a time span the floor takes the
/// weight of the gas plus what the ceiling takes, up to the change of the gas's momentum:
/// p_floor − p_ceiling = (N m g Δt − Δ(Σ m v_z)) / Δt per unit time. Exact (no statistics),
/// to the round-off of the sums.
#[test]
fn floor_minus_ceiling_is_the_weight() {
    let g = 1.0;
    let mut e = column::<2>(400, 0.2, 1.0, WallKind::Elastic, WallKind::Elastic, g, 9);
    e.run_collisions(20_000);
    let momentum = |e: &mut EventDriven<2>| -> f64 {
        let s = e.system();
        (0..s.len()).map(|i| s.masses[i] * s.velocities[i][1]).sum()
    };
    let (t0, p0) = (e.time(), momentum(&mut e));
    let before: Vec<f64> = e
        .walls()
        .unwrap()
        .tallies()
        .iter()
        .map(|t| t.momentum)
        .collect();
    e.run_collisions(200_000);
    let (t1, p1) = (e.time(), momentum(&mut e));
    let after: Vec<f64> = e
        .walls()
        .unwrap()
        .tallies()
        .iter()
        .map(|t| t.momentum)
        .collect();
    let (floor, ceiling) = (after[0] - before[0], after[1] - before[1]);
    let weight = 400.0 * g * (t1 - t0);
    // Impulses on the gas: floor up, ceiling down, gravity down.
    let balance = floor - ceiling - weight - (p1 - p0);
    assert!(balance.abs() < 1e-9 * weight, "{balance} of {weight}");
    assert!(ceiling > 0.0 && floor > weight);
}

/// A settling bed of inelastic spheres (eps = 0.7, TC model) on an inelastic floor (eps_w
/// = 0.5): without a rule, a sphere's bounces on the floor accumulate in finite time
/// (infinitely many events). The resting rule (a floor sends spheres off at least as fast
/// as a bounce of 1e-4 diameters needs) bounds the work. Oracles: the rule's own bound on
/// floor contacts (a lone sphere touches the floor once per sqrt(8 h / g) at most; a
/// collision can send each of its two spheres back once more), a steady event rate (the
/// second of two equal spans no costlier than 1.2 times the first, where an accumulation
/// would grow without bound), and the energy the floor gave by lifts, at most m g h each.
#[test]
fn a_settling_bed_runs_at_a_bounded_rate() {
    let g = 1.0;
    let floor = WallKind::Restitution(Box::new(Constant::new(0.5).unwrap()));
    let mut e = column::<2>(200, 0.1, 0.7, floor, WallKind::Elastic, g, 4);
    e.set_tc_model(1e-4, None).unwrap();
    let span = 20.0;
    e.run_until(span);
    let mut spans = Vec::new();
    for k in 2..4 {
        let (events, collisions) = (e.counters().events, e.counters().collisions);
        let contacts = e.walls().unwrap().tallies()[0].collisions;
        e.run_until(k as f64 * span);
        assert!(e.collapsed().is_none(), "collapsed at {:?}", e.collapsed());
        let contacts = e.walls().unwrap().tallies()[0].collisions - contacts;
        let collisions = e.counters().collisions - collisions;
        let bound = 200.0 * (g / (8.0 * 1e-4)).sqrt() * span + 2.0 * collisions as f64;
        eprintln!(
            "span {k}: events {}, collisions {collisions}, floor contacts {contacts} (bound \
             {bound})",
            e.counters().events - events
        );
        assert!((contacts as f64) <= bound);
        spans.push(e.counters().events - events);
    }
    assert!(spans[1] as f64 <= 1.2 * spans[0] as f64, "{spans:?}");
    let lift = e.walls().unwrap().records()[0].lift;
    eprintln!("lifts {lift:?}");
    assert!(lift.lifts > 0 && lift.energy <= lift.lifts as f64 * g * 1e-4 * (1.0 + 1e-12));
}

/// Hard spheres between thermal floor and ceiling at T = 1 in gravity, phi ~ 0.22 at the
/// bottom and ~ 0.09 at the top (Z from 2.3 to 1.4: an ideal gas would be off by as
/// much): in equilibrium the pressure at height z is
/// the ceiling's plus the weight of the gas above (hydrostatics, exact), and the equation
/// of state gives it from the local density: P = n T Z(phi) with Carnahan–Starling's Z
/// (local density approximation, valid where n varies little over a diameter: the scale
/// height T / (m g) is 5 diameters here). Slabs one diameter thick, at least 2 diameters
/// from the walls (their layering is not a bulk state). Tolerance per slab: 4 standard
/// errors (10 blocks) plus 2 %, CS's error at phi < 0.4 (< 1 %) and the local density
/// approximation's (the gradient term (sigma / H)^2 ~ 4 % of the slab's weight term;
/// measured: docs/walls.md).
#[test]
fn a_dense_column_is_in_hydrostatic_balance_with_carnahan_starling() {
    let g = 0.2;
    let mut e = column::<3>(
        2000,
        0.15,
        1.0,
        WallKind::Thermal { temperature: 1.0 },
        WallKind::Thermal { temperature: 1.0 },
        g,
        17,
    );
    e.run_collisions(300_000);
    let length = e.system().sides[2];
    let bins = length.floor() as usize;
    let width = length / bins as f64;
    let area = length * length;
    let mut blocks: Vec<(Vec<f64>, f64)> = Vec::new();
    for _ in 0..10 {
        let mut density = vec![0.0; bins];
        let ceiling = e.walls().unwrap().tallies()[1].momentum;
        let t0 = e.time();
        for _ in 0..20 {
            e.run_collisions(5_000);
            let slabs = gas::profile::profile(e.system(), 2, bins, 1.0);
            for (d, s) in density.iter_mut().zip(&slabs) {
                *d += s.density / 20.0;
            }
        }
        let ceiling =
            (e.walls().unwrap().tallies()[1].momentum - ceiling) / (area * (e.time() - t0));
        blocks.push((density, ceiling));
    }
    // Per block and slab: weight pressure (ceiling + m g ∫ n above the slab's centre) over
    // the equation of state's.
    let ratios: Vec<Vec<f64>> = blocks
        .iter()
        .map(|(n, ceiling)| {
            (0..bins)
                .map(|b| {
                    let above: f64 = n[b + 1..].iter().sum::<f64>() * width + 0.5 * n[b] * width;
                    let weight = ceiling + g * above;
                    let phi = n[b] * std::f64::consts::PI / 6.0;
                    let z = (1.0 + phi + phi * phi - phi.powi(3)) / (1.0 - phi).powi(3);
                    weight / (n[b] * z)
                })
                .collect()
        })
        .collect();
    for b in 0..bins {
        let centre = (b as f64 + 0.5) * width;
        if centre < 2.5 || centre > length - 2.5 {
            continue;
        }
        let values: Vec<f64> = ratios.iter().map(|r| r[b]).collect();
        let mean = values.iter().sum::<f64>() / 10.0;
        let error = (values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / 90.0).sqrt();
        let phi = blocks.iter().map(|(n, _)| n[b]).sum::<f64>() / 10.0 * std::f64::consts::PI / 6.0;
        eprintln!("z {centre:.2} phi {phi:.3}: weight / EOS = {mean:.4} ± {error:.4}");
        assert!(
            (mean - 1.0).abs() < 4.0 * error + 0.02,
            "slab {b}: {mean} ± {error}"
        );
    }
}
