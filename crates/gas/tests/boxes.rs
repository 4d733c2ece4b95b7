//! Boxes with sides of their own (`System::sides`): stored as before when cubic, the
//! engines' cells and images along each axis, placements that fill them.
//!
//! The oracles: a box twice as long as a cube along one axis, holding the cube's gas and its
//! periodic image, must repeat the cube's dynamics exactly (a periodic solution stays
//! periodic; only rounding differs); the O(N^2) search for a missed collision; brute-force
//! overlap checks; Enskog's collision frequency for DSMC.

use gas::dsmc::{point_gas, SpatialOptions};
use gas::init::{monodisperse_reporting, BoxSize};
use gas::observe::temperature;
use gas::soft::contact::ViscoelasticMaterial;
use gas::system::{ball_volume, dot};
use gas::theory::{collision_frequency, mean_free_path};
use gas::{Engine, EventDriven, SoftSphere, SoftSphereOptions, SpatialDsmc, System};
use restitution::Constant;

fn law(eps: f64) -> Box<Constant> {
    Box::new(Constant::new(eps).unwrap())
}

/// A cube's state and its copy one side up along the last axis, in the box twice as long.
fn doubled<const D: usize>(cube: &System<D>) -> System<D> {
    let l = cube.sides[0];
    let mut sides = cube.sides;
    sides[D - 1] = 2.0 * l;
    let shifted = cube.positions.iter().map(|x| {
        let mut y = *x;
        y[D - 1] += l;
        y
    });
    System {
        sides,
        positions: cube.positions.iter().copied().chain(shifted).collect(),
        velocities: [cube.velocities.clone(), cube.velocities.clone()].concat(),
        radii: [cube.radii.clone(), cube.radii.clone()].concat(),
        masses: [cube.masses.clone(), cube.masses.clone()].concat(),
    }
}

/// Largest difference between the velocities of particle i of `cube` and of particles i
/// and i + N of `long`, relative to the thermal speed.
fn velocity_mismatch<const D: usize>(cube: &System<D>, long: &System<D>) -> f64 {
    let n = cube.len();
    let speed = temperature(cube).sqrt();
    (0..n)
        .flat_map(|i| [(i, i), (i, i + n)])
        .map(|(i, j)| {
            let d: [f64; D] =
                std::array::from_fn(|k| cube.velocities[i][k] - long.velocities[j][k]);
            dot(&d, &d).sqrt() / speed
        })
        .fold(0.0, f64::max)
}

/// A cubic box is serialized as its one side, exactly as before boxes had sides of their
/// own (so check-points of cubes keep their bytes): the JSON has `"length": L`; a box with
/// sides round-trips through JSON as a list.
#[test]
fn a_cube_is_stored_as_one_side_and_other_boxes_as_their_sides() {
    let cube = System::<2> {
        sides: [4.0; 2],
        positions: vec![[1.0, 2.0]],
        velocities: vec![[0.5, -0.5]],
        radii: vec![0.5],
        masses: vec![1.0],
    };
    let json = serde_json::to_string(&cube).unwrap();
    assert!(json.starts_with("{\"length\":4.0,"), "{json}");
    let back: System<2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, cube);
    let oblong = System {
        sides: [4.0, 9.0],
        ..cube.clone()
    };
    let json = serde_json::to_string(&oblong).unwrap();
    assert!(json.starts_with("{\"length\":[4.0,9.0],"), "{json}");
    let back: System<2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, oblong);
    let three = json.replace("[4.0,9.0]", "[4.0,9.0,1.0]");
    assert!(serde_json::from_str::<System<2>>(&three).is_err());
    // Positions are checked against the side of their own axis.
    let mut outside = oblong.clone();
    outside.positions[0] = [1.0, 5.0];
    assert!(outside.check(true).is_ok());
    outside.positions[0] = [5.0, 1.0];
    assert!(outside.check(true).is_err());
}

/// Event-driven MD: the box [L, L, 2L] holding a cube's gas and its image repeats the
/// cube's collisions (twice as many, to the last one) and velocities (to rounding grown by
/// the chaos of three collisions per particle: 1e-8 of the thermal speed), in 2D and 3D,
/// with an inelastic law.
#[test]
fn a_doubled_box_repeats_the_cube_in_event_driven_md() {
    fn check<const D: usize>(n: usize, phi: f64) {
        let cube = gas::init::monodisperse::<D>(n, phi, 1.0, 1.0, 1.0, 3).unwrap();
        let long = doubled(&cube);
        let mut a = EventDriven::new(cube, law(0.8)).unwrap();
        let mut b = EventDriven::new(long, law(0.8)).unwrap();
        // A time between collisions (rounding may shift an image's collision across it).
        a.run_collisions(3 * n as u64 / 2);
        let t = a.time() + 1e-6;
        a.run_until(t);
        b.run_until(t);
        assert_eq!(b.counters().collisions, 2 * a.counters().collisions, "{D}D");
        let mismatch = velocity_mismatch(a.system(), b.system());
        eprintln!("{D}D: velocity mismatch {mismatch:.2e}");
        assert!(mismatch < 1e-8, "{D}D: {mismatch}");
    }
    check::<2>(400, 0.2);
    check::<3>(500, 0.15);
}

/// Event-driven MD in oblong boxes (few cells along one axis, many along another): no pair
/// ever collides before the events the engine scheduled (the O(N^2) search).
#[test]
fn no_collision_is_missed_in_an_oblong_box() {
    fn check<const D: usize>(sides: [f64; D], n: usize) {
        let (system, _) =
            monodisperse_reporting::<D>(n, sides, 1.0, 1.0, 1.0, 9, [false; D]).unwrap();
        assert_eq!(system.sides, sides);
        let mut e = EventDriven::new(system, law(0.9)).unwrap();
        for _ in 0..40 {
            for _ in 0..50 {
                e.step();
            }
            assert_eq!(e.missed_collision(), None, "{sides:?}");
        }
        assert!(e.counters().collisions > 500);
    }
    check::<3>([15.0, 5.0, 8.0], 300);
    check::<2>([40.0, 10.0], 150);
}

/// Placements fill the box they are given: every centre inside, no two spheres
/// overlapping (brute force), the packing fraction the spheres' volume over the box's;
/// random addition, a melted lattice of unequal rows, and growth.
#[test]
fn placements_fill_a_box_of_sides() {
    for (sides, n) in [
        ([20.0, 10.0, 10.0], 500), // phi 0.13: random addition
        ([18.0, 9.0, 9.0], 1000),  // phi 0.36: a lattice, melted
        ([16.0, 8.0, 8.5], 1000),  // phi 0.48: grown
    ] {
        let (s, _) =
            monodisperse_reporting::<3>(n, BoxSize::Sides(sides), 1.0, 1.0, 1.0, 4, [false; 3])
                .unwrap();
        assert_eq!(s.sides, sides);
        let phi = n as f64 * ball_volume::<3>(0.5) / (sides[0] * sides[1] * sides[2]);
        assert!((s.packing_fraction() / phi - 1.0).abs() < 1e-12);
        for (i, x) in s.positions.iter().enumerate() {
            assert!((0..3).all(|k| (0.0..sides[k]).contains(&x[k])), "{x:?}");
            for j in 0..i {
                let d = s.separation(x, &s.positions[j]);
                assert!(dot(&d, &d) >= 1.0 - 1e-9, "{sides:?}: {i} and {j} overlap");
            }
        }
        assert!((temperature(&s) - 1.0).abs() < 1e-9);
    }
}

/// Spatial DSMC in an oblong box (the same volume as a cube of 5 mean free paths, sides
/// 2 : 1 : 1/2): elastic collisions at the Enskog rate, per particle (N - 1)/N of it.
/// 1e4 particles over 20 collision times give about 1e5 collisions: a standard error of
/// 0.3%; the 2% of the cubic test is kept.
#[test]
fn spatial_dsmc_collides_at_the_enskog_rate_in_an_oblong_box() {
    let (n, phi) = (10_000, 0.1);
    let density = phi / ball_volume::<3>(0.5);
    let l = 5.0 * mean_free_path::<3>(density, 1.0, phi);
    let system = point_gas::<3>(n, [2.0 * l, l, 0.5 * l], 1.0, 1.0, 1.0, 5).unwrap();
    let mut e = SpatialDsmc::new(system, phi, law(1.0), 5, SpatialOptions::default()).unwrap();
    let omega0 = collision_frequency::<3>(density, 1.0, 1.0, 1.0, phi);
    e.run_until(20.0 / omega0);
    let s = e.system().clone();
    for x in &s.positions {
        assert!((0..3).all(|k| (0.0..s.sides[k]).contains(&x[k])), "{x:?}");
    }
    let ratio = e.collisions_per_particle() / (e.time() * omega0 * (1.0 - 1.0 / n as f64));
    eprintln!("spatial DSMC, box 2:1:1/2: omega / omega_Enskog = {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.02, "{ratio}");
}

/// Soft-sphere MD: the doubled box repeats the cube (forces from the neighbour lists of
/// its own cells along each axis), to rounding after 200 steps.
#[test]
fn a_doubled_box_repeats_the_cube_in_soft_sphere_md() {
    let material = ViscoelasticMaterial::new(1e4, 0.3, 1e-3).unwrap();
    let cube = gas::init::monodisperse::<3>(400, 0.2, 1.0, 1.0, 1.0, 6).unwrap();
    let long = doubled(&cube);
    let options = SoftSphereOptions::default();
    let mut a = SoftSphere::new(cube, material, options).unwrap();
    let mut b = SoftSphere::new(long, material, options).unwrap();
    let dt = a.time_step();
    a.run_until(200.0 * dt);
    b.run_until(200.0 * dt);
    assert_eq!(b.counters().collisions, 2 * a.counters().collisions);
    assert!(a.counters().collisions > 50);
    let mismatch = velocity_mismatch(a.system(), b.system());
    eprintln!("soft spheres: velocity mismatch {mismatch:.2e}");
    assert!(mismatch < 1e-8, "{mismatch}");
}
