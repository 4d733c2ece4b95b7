//! Uniform shear flow in soft-sphere MD: Lees–Edwards boundaries, the tensor virial, their
//! check-points.
//!
//! Oracles: Galilean invariance (a contact across the sliding face is the same contact in
//! the bulk, seen from the image's frame); the conservation of the momentum relative to the
//! flow, Σ m V (forces come in pairs, a crossing keeps V); the O(N²) search for overlapping
//! pairs over every image across the sliding faces (the neighbour lists miss none); the
//! trace of the tensor virial, which is the scalar virial summed independently; a restored
//! engine that must continue bit for bit; an unsheared state's bytes, which end where they
//! did before the tail.

use gas::shear::Shear;
use gas::soft::contact::ViscoelasticMaterial;
use gas::{Checkpoint, Engine, SoftSphere, SoftSphereOptions, System};

fn material() -> ViscoelasticMaterial {
    ViscoelasticMaterial::new(1e4, 0.3, 0.02).unwrap()
}

fn gas<const D: usize>(n: usize, phi: f64, rate: f64, seed: u64) -> SoftSphere<D> {
    let system = gas::init::monodisperse::<D>(n, phi, 1.0, 1.0, 1.0, seed).unwrap();
    let mut engine = SoftSphere::new(system, material(), SoftSphereOptions::default()).unwrap();
    engine.set_shear(Some(Shear::new(rate).unwrap())).unwrap();
    engine.set_virial_tensor(true);
    engine
}

/// Two spheres of a sheared 3D box (L = 10, a = 0.3: the images slide at a L = 3), A above
/// B, approaching head-on along y (peculiar velocities chosen so that their lab relative
/// velocity has no x part) at centre `centre`; B's lab place is wrapped into the box. The
/// pair's common velocity −2 e_y carries A through the bottom face during the contact
/// when the pair straddles it. Returns the engine after the contact, and A's and B's lab
/// velocities before it.
fn pair(centre: f64) -> (SoftSphere<3>, [[f64; 3]; 2]) {
    let (length, rate) = (10.0, 0.3);
    let (gap, x) = (0.1, 4.0);
    let (ya, yb) = (centre + 0.5 + 0.5 * gap, centre - 0.5 - 0.5 * gap);
    let system = System {
        sides: [length; 3],
        positions: vec![
            [x, ya.rem_euclid(length), 5.0],
            [x, yb.rem_euclid(length), 5.0],
        ],
        // Lab v_x = a y + V_x: equal for A and B's image when V_Ax − V_Bx = −a (y_A − y_B).
        velocities: vec![
            [-0.5 * rate * (ya - yb), -3.0, 0.0],
            [0.5 * rate * (ya - yb), -1.0, 0.0],
        ],
        radii: vec![0.5; 2],
        masses: vec![1.0; 2],
    };
    let mut engine = SoftSphere::new(system, material(), SoftSphereOptions::default()).unwrap();
    // δ(0) = 0: B's image below the box is at B's x; the images slide at a L and B's lab
    // velocity carries it with them.
    engine.set_shear(Some(Shear::new(rate).unwrap())).unwrap();
    let before = lab(&mut engine);
    (engine, before)
}

/// The lab velocities (peculiar + the flow at the sphere's height).
fn lab(engine: &mut SoftSphere<3>) -> [[f64; 3]; 2] {
    let rate = engine.shear().unwrap().rate;
    let s = engine.system();
    std::array::from_fn(|i| {
        let mut v = s.velocities[i];
        v[0] += rate * s.positions[i][1];
        v
    })
}

/// A head-on contact across the sliding face (the pair straddling y = 0, sphere A crossing
/// the face mid-contact) changes the lab velocities exactly as the same contact in the bulk
/// (the pair at y = 5.15): Galilean invariance of the contact law, with the images' velocity
/// jump a L_y in the overlap's rate and in A's crossing. The contact is one collision,
/// kept through the crossing (its history: one contact begun), with the law's eps.
#[test]
fn a_contact_across_the_sliding_face_is_the_bulk_contact() {
    let (mut face, face_before) = pair(-0.35);
    let (mut bulk, bulk_before) = pair(5.15);
    // A crosses y = 0 about mid-contact (the contact lasts ~0.08): step until it has.
    let mut crossed_in_contact = false;
    while face.time() < 0.5 {
        let above = face.system().positions[0][1] < 5.0;
        face.run_steps(1);
        let crossed = above && face.system().positions[0][1] > 5.0;
        crossed_in_contact |= crossed && !face.contacts().is_empty();
    }
    bulk.run_until(face.time());
    assert!(crossed_in_contact, "A did not cross the face in contact");
    for engine in [&face, &bulk] {
        assert_eq!(engine.counters().collisions, 1);
        assert!(engine.contacts().is_empty());
    }
    let (face_after, bulk_after) = (lab(&mut face), lab(&mut bulk));
    let jump = 0.3 * 10.0;
    for i in 0..2 {
        for k in 0..3 {
            // A re-entered through the top face: its lab v_x gained a L_y.
            let crossing = if i == 0 && k == 0 { jump } else { 0.0 };
            let change_face = face_after[i][k] - crossing - face_before[i][k];
            let change_bulk = bulk_after[i][k] - bulk_before[i][k];
            assert!(
                (change_face - change_bulk).abs() < 1e-10,
                "sphere {i}, axis {k}: {change_face} across the face, {change_bulk} in the bulk"
            );
        }
    }
    // Head-on: the relative velocity stays along y, reversed with the eps of the exact
    // viscoelastic law at v = 2 (to the default step's accuracy, MAX_EPS_ERROR).
    let eps = (bulk_after[0][1] - bulk_after[1][1]) / -(bulk_before[0][1] - bulk_before[1][1]);
    let vstar = material().beta(0.5, 0.5, 1.0, 1.0).sqrt() * 2f64.powf(0.1);
    let exact = restitution::exact::solve(vstar, restitution::exact::Criterion::Improved)
        .unwrap()
        .eps;
    assert!((eps - exact).abs() < 1e-2, "eps = {eps}, exact {exact}");
    assert!((bulk_after[0][0] - bulk_after[1][0]).abs() < 1e-12);
}

/// The positions of a sheared engine now, and the pairs overlapping over every image: the
/// direct one (minimum image along x and z) and the images above and below the box, at
/// x ± δ (O(N²)).
fn overlapping<const D: usize>(engine: &mut SoftSphere<D>) -> Vec<(u32, u32)> {
    let (rate, time) = (engine.shear().unwrap().rate, engine.time());
    let s = engine.system();
    let delta = (rate * s.sides[1] * time).rem_euclid(s.sides[0]);
    let mut pairs = Vec::new();
    for i in 0..s.len() {
        for j in i + 1..s.len() {
            let contact = s.radii[i] + s.radii[j];
            let touching = [-1.0, 0.0, 1.0].iter().any(|&shift: &f64| {
                let d2: f64 = (0..D)
                    .map(|k| {
                        let mut d = s.positions[j][k] - s.positions[i][k];
                        if k == 0 {
                            d += shift * delta;
                        }
                        if k == 1 {
                            d += shift * s.sides[1];
                        } else {
                            d -= s.sides[k] * (d / s.sides[k]).round();
                        }
                        d * d
                    })
                    .sum();
                d2 < contact * contact
            });
            if touching {
                pairs.push((i as u32, j as u32));
            }
        }
    }
    pairs
}

/// Every 5 steps, the engine's contacts are all the overlapping pairs over every image
/// (the neighbour lists across the sliding faces miss none), at rates whose images slide
/// past the box several times; the momentum relative to the flow, Σ m V, stays at its
/// initial value to round-off (forces in pairs; a crossing keeps V; Σ m v_y = 0 keeps
/// Σ m V_x, whose rate is −a Σ m v_y).
fn finds_every_contact_and_keeps_the_momentum<const D: usize>(n: usize, rate: f64) {
    let engine = gas::<D>(n, 0.3, rate, 7);
    every_contact_found(engine, rate);
}

fn every_contact_found<const D: usize>(mut engine: SoftSphere<D>, rate: f64) {
    let n = engine.particles();
    let momentum = |e: &mut SoftSphere<D>| -> [f64; D] {
        let s = e.system();
        std::array::from_fn(|k| (0..s.len()).map(|i| s.masses[i] * s.velocities[i][k]).sum())
    };
    let start = momentum(&mut engine);
    let mut contacts = 0;
    for _ in 0..600 {
        engine.run_steps(5);
        let expected = overlapping(&mut engine);
        assert_eq!(engine.contacts(), expected.as_slice(), "{D}D rate {rate}");
        contacts += expected.len();
        let now = momentum(&mut engine);
        for k in 0..D {
            assert!(
                (now[k] - start[k]).abs() < 1e-11 * n as f64,
                "{D}D: momentum {now:?}, initially {start:?}"
            );
        }
    }
    let sides = engine.system().sides;
    let slid = rate * sides[1] * engine.time() / sides[0];
    assert!(slid.abs() > 2.0, "the images slid {slid} boxes only");
    assert!(contacts > 100, "{contacts} contacts seen");
}

#[test]
fn every_contact_across_the_sliding_faces_is_found_2d() {
    finds_every_contact_and_keeps_the_momentum::<2>(300, 1.5);
    finds_every_contact_and_keeps_the_momentum::<2>(300, -0.8);
    // A box longer along x than along y (cells of other widths along the faces).
    let (system, _) =
        gas::init::monodisperse_reporting::<2>(150, [40.0, 14.0], 1.0, 1.0, 1.0, 2, [false; 2])
            .unwrap();
    let mut engine = SoftSphere::new(system, material(), SoftSphereOptions::default()).unwrap();
    engine.set_shear(Some(Shear::new(2.5).unwrap())).unwrap();
    every_contact_found(engine, 2.5);
}

#[test]
fn every_contact_across_the_sliding_faces_is_found_3d() {
    finds_every_contact_and_keeps_the_momentum::<3>(400, 2.0);
    finds_every_contact_and_keeps_the_momentum::<3>(400, -1.0);
}

/// The tensor virial's trace is the scalar virial summed since it was switched on (the
/// counters' ∫ Σ F_n d dt, summed apart), sheared or not; under shear P_xy's collisional
/// part is negative (momentum flows down the gradient).
#[test]
fn the_tensor_virial_traces_to_the_scalar_virial() {
    for rate in [None, Some(0.5)] {
        let system = gas::init::monodisperse::<3>(400, 0.3, 1.0, 1.0, 1.0, 3).unwrap();
        let mut engine = SoftSphere::new(system, material(), SoftSphereOptions::default()).unwrap();
        if let Some(rate) = rate {
            engine.set_shear(Some(Shear::new(rate).unwrap())).unwrap();
        }
        engine.run_until(1.0);
        let scalar = engine.counters().virial;
        engine.set_virial_tensor(true);
        engine.run_until(6.0);
        let tensor = engine.virial_tensor().unwrap();
        let trace = tensor.get(0, 0) + tensor.get(1, 1) + tensor.get(2, 2);
        let summed = engine.counters().virial - scalar;
        assert!(
            (trace - summed).abs() < 1e-9 * summed,
            "trace {trace}, virial {summed}"
        );
        if rate.is_some() {
            assert!(tensor.get(0, 1) < -0.01 * summed, "{tensor:?}");
        }
    }
}

/// A sheared engine saved and restored continues bit for bit (positions, lab velocities,
/// forces, contacts, the tensor virial), its state saying it is sheared; a periodic
/// unsheared state ends as before the tail (its last field eps_error, postcard).
#[test]
fn a_sheared_engine_continues_bit_for_bit_after_a_restore() {
    let mut engine = gas::<3>(400, 0.2, 0.8, 11);
    engine.run_until(3.0);
    let state = engine.save();
    assert_eq!(state.tail.shear, Some(Shear { rate: 0.8 }));
    let bytes = postcard::to_stdvec(&state).unwrap();
    let mut padded = bytes.clone();
    padded.extend([0; gas::tail::TAIL_PADDING]);
    let read: gas::SoftSphereState<3> = postcard::from_bytes(&padded).unwrap();
    let mut copy = SoftSphere::restore(read, ()).unwrap();
    engine.run_until(8.0);
    copy.run_until(8.0);
    assert!(engine.counters().collisions > 200);
    assert_eq!(engine.time(), copy.time());
    assert_eq!(engine.counters(), copy.counters());
    assert_eq!(engine.virial_tensor(), copy.virial_tensor());
    assert_eq!(engine.contacts(), copy.contacts());
    assert!(engine.system() == copy.system(), "the restored run differs");
    assert!(engine.save() == copy.save(), "the restored state differs");

    let system = gas::init::monodisperse::<3>(100, 0.2, 1.0, 1.0, 1.0, 1).unwrap();
    let mut plain = SoftSphere::new(system, material(), SoftSphereOptions::default()).unwrap();
    plain.run_until(1.0);
    let state = plain.save();
    assert!(state.tail.is_empty());
    let bytes = postcard::to_stdvec(&state).unwrap();
    assert!(bytes.ends_with(&state.eps_error.to_le_bytes()));
}

/// Bad shear is refused, and never panics: 1D, a rate that is not finite and nonzero,
/// walls with shear (either order); the engine keeps its shear.
#[test]
fn bad_shear_is_refused() {
    use gas::walls::{Side, Wall, WallKind, Walls};
    let system = gas::init::monodisperse::<1>(20, 0.2, 1.0, 1.0, 1.0, 1).unwrap();
    let mut line = SoftSphere::new(system, material(), SoftSphereOptions::default()).unwrap();
    assert!(line.set_shear(Some(Shear { rate: 0.5 })).is_err());
    let mut engine = gas::<3>(100, 0.2, 0.5, 1);
    for rate in [0.0, f64::NAN, f64::INFINITY] {
        assert!(engine.set_shear(Some(Shear { rate })).is_err());
    }
    let walls = || {
        let wall = |side| Wall {
            axis: 2,
            side,
            kind: WallKind::Elastic,
        };
        Walls::new(vec![wall(Side::Low), wall(Side::High)], 1).unwrap()
    };
    assert!(engine.set_walls(Some(walls())).is_err());
    assert_eq!(engine.shear(), Some(Shear { rate: 0.5 }));
    let system = gas::init::monodisperse::<3>(100, 0.2, 1.0, 1.0, 1.0, 1).unwrap();
    let mut boxed = SoftSphere::new(system, material(), SoftSphereOptions::default()).unwrap();
    boxed.set_walls(Some(walls())).unwrap();
    let error = boxed.set_shear(Some(Shear { rate: 0.5 })).unwrap_err();
    assert!(error.to_string().contains("shear"), "{error}");
    assert_eq!(boxed.shear(), None);
}
