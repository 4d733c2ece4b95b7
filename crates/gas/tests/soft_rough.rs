//! Rough soft spheres (`gas::soft::tangential`): the engine's oblique contacts against an
//! independent integration of the same contact model (Runge–Kutta 4 of the continuous
//! equations, below), against Walton's model where the contact slides throughout, and the
//! invariants of the force (angular momentum to round-off, the energy balance converging
//! at second order in the step, zero friction leaving translation bit for bit, check-points
//! resuming bit for bit).
//!
//! Two equal spheres (radius 1/2, mass 1, inertia factor q: I = q m a²) meet with
//! contact-point velocity (−g_n, g_t), g_n = 1.

use gas::rotation::Rotation;
use gas::soft::contact::{contact_duration, normal_force, ViscoelasticMaterial};
use gas::soft::oblique::oblique_contact;
use gas::soft::tangential::mindlin_stiffness;
use gas::{Checkpoint, Engine, SoftSphere, SoftSphereOptions, System};
use restitution::rough::cross;

const RADIUS: f64 = 0.5;
const MASS: f64 = 1.0;

fn material(a: f64) -> ViscoelasticMaterial {
    ViscoelasticMaterial::new(1e5, 0.3, a).unwrap()
}

/// The duration of a contact at g_n = 1.
fn duration(m: &ViscoelasticMaterial) -> f64 {
    let rho = m.elastic_constant(RADIUS, RADIUS);
    contact_duration(rho, m.dissipative_constant, 0.5 * MASS, 1.0).unwrap()
}

/// The state of the contact ODE: the separation r = x_j − x_i, its rate u, the angular
/// velocities of i and j and the spring δ.
type State = [[f64; 3]; 5];

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The continuous equations of the contact model of `gas::soft::tangential`, written out
/// here from its definition without the engine's code: m_eff u' = F_n n + F_t,
/// I ω_i' = −l_i n × F_t, I ω_j' = −l_j n × F_t, δ' = g_t − n (δ·n') (the spring
/// advanced by the slip and kept in the tangent plane), no Coulomb limit (sticking)
/// except that the tangential force vanishes with the normal one.
fn rates(y: &State, m: &ViscoelasticMaterial, q: f64) -> State {
    let [r, u, wi, wj, delta] = *y;
    let d = dot(&r, &r).sqrt();
    let n = r.map(|x| x / d);
    let xi = 2.0 * RADIUS - d;
    if xi <= 0.0 {
        return [u, [0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]];
    }
    let xi_dot = -dot(&u, &n);
    let (f_n, _) = normal_force(
        m.elastic_constant(RADIUS, RADIUS),
        m.dissipative_constant,
        xi,
        xi_dot,
    );
    let arm = RADIUS - 0.5 * xi;
    let spin: [f64; 3] = std::array::from_fn(|k| arm * (wi[k] + wj[k]));
    let s = cross(&spin, &n);
    let g: [f64; 3] = std::array::from_fn(|k| u[k] - s[k]);
    let g_n = dot(&g, &n);
    let g_t: [f64; 3] = std::array::from_fn(|k| g[k] - g_n * n[k]);
    // Any finite friction cuts the tangential force to 0 with the normal force.
    let k_t = mindlin_stiffness(m, RADIUS, RADIUS, xi) * if f_n > 0.0 { 1.0 } else { 0.0 };
    let f_t: [f64; 3] =
        std::array::from_fn(|k| -k_t * delta[k] - m.dissipative_constant * k_t * g_t[k]);
    let twist = cross(&n, &f_t);
    let moment = q * MASS * RADIUS * RADIUS;
    let n_dot: [f64; 3] = std::array::from_fn(|k| (u[k] - dot(&u, &n) * n[k]) / d);
    let turn = dot(&delta, &n_dot);
    let m_eff = 0.5 * MASS;
    [
        u,
        std::array::from_fn(|k| (f_n * n[k] + f_t[k]) / m_eff),
        twist.map(|t| -arm * t / moment),
        twist.map(|t| -arm * t / moment),
        std::array::from_fn(|k| g_t[k] - n[k] * turn),
    ]
}

/// ε and β of a sticking contact from the ODE, Runge–Kutta 4 with `steps` steps per
/// contact duration, from touching (δ = 0) until the spheres part or the normal force
/// vanishes while they recede.
fn ode_contact(m: &ViscoelasticMaterial, q: f64, g_t: f64, steps: f64) -> (f64, f64) {
    let h = duration(m) / steps;
    let mut y: State = [
        [2.0 * RADIUS, 0.0, 0.0],
        [-1.0, g_t, 0.0],
        [0.0; 3],
        [0.0; 3],
        [0.0; 3],
    ];
    let add = |y: &State, k: &State, c: f64| -> State {
        std::array::from_fn(|a| std::array::from_fn(|b| y[a][b] + c * k[a][b]))
    };
    let rho = m.elastic_constant(RADIUS, RADIUS);
    for _ in 0..(100.0 * steps) as usize {
        let k1 = rates(&y, m, q);
        let k2 = rates(&add(&y, &k1, 0.5 * h), m, q);
        let k3 = rates(&add(&y, &k2, 0.5 * h), m, q);
        let k4 = rates(&add(&y, &k3, h), m, q);
        y = std::array::from_fn(|a| {
            std::array::from_fn(|b| {
                y[a][b] + h / 6.0 * (k1[a][b] + 2.0 * k2[a][b] + 2.0 * k3[a][b] + k4[a][b])
            })
        });
        let [r, u, wi, wj, _] = y;
        let d = dot(&r, &r).sqrt();
        let n = r.map(|x| x / d);
        let xi = 2.0 * RADIUS - d;
        let xi_dot = -dot(&u, &n);
        if xi <= 0.0
            || (xi_dot < 0.0 && normal_force(rho, m.dissipative_constant, xi, xi_dot).0 == 0.0)
        {
            // Measured once the spheres have parted: contact points a from the centres.
            let spin: [f64; 3] = std::array::from_fn(|k| RADIUS * (wi[k] + wj[k]));
            let s = cross(&spin, &n);
            let g: [f64; 3] = std::array::from_fn(|k| u[k] - s[k]);
            let t = [-n[1], n[0], 0.0];
            return (dot(&g, &n), -dot(&g, &t) / g_t);
        }
    }
    panic!("the ODE's contact did not end");
}

/// Sticking contacts (μ = 1e9), damped (ε ≈ 0.75) and elastic, two inertia factors: the
/// engine's ε and β equal the ODE's. Both converge at first order in their steps in β:
/// the tangential force, which the spring holds as the normal force vanishes, stops within
/// a step (measured: the engine's β moves by 2.6e-4, 1.3e-4, 6.5e-5 from 500 to 8000 steps
/// per contact). So each is extrapolated (Richardson, 2 β(h) − β(2h)) from two steps: the
/// engine's from 1000 and 2000 steps per contact, the ODE's from 10 000 and 20 000; what
/// remains is of second order, ~1e-6 (the extrapolations from 2000/4000 and 1000/2000
/// agree to that), and the bound 2e-5 would catch a wrong stiffness (β moves by ~0.1 for
/// a 10% change of k_t) or a torque's wrong arm.
#[test]
fn sticking_contacts_restitute_as_the_contact_ode() {
    for (a, q) in [(2e-3, 0.4), (0.0, 0.4), (2e-3, 2.0 / 3.0)] {
        let m = material(a);
        let extrapolate = |fine: (f64, f64), coarse: (f64, f64)| {
            (2.0 * fine.0 - coarse.0, 2.0 * fine.1 - coarse.1)
        };
        let ode = extrapolate(
            ode_contact(&m, q, 0.01, 20_000.0),
            ode_contact(&m, q, 0.01, 10_000.0),
        );
        let engine = |steps: f64| {
            let md = oblique_contact(m, 1e9, (RADIUS, MASS, q), (1.0, 0.01), duration(&m) / steps)
                .unwrap();
            assert!(!md.slid && md.beta.abs() < 1.0);
            (md.eps, md.beta)
        };
        let md = extrapolate(engine(2000.0), engine(1000.0));
        println!(
            "A = {a}, q = {q}: ODE eps {:.7} beta {:.7}; MD eps {:.7} beta {:.7}",
            ode.0, ode.1, md.0, md.1
        );
        assert!((md.0 - ode.0).abs() < 2e-5, "eps {} vs {}", md.0, ode.0);
        assert!((md.1 - ode.1).abs() < 2e-5, "beta {} vs {}", md.1, ode.1);
    }
}

/// Contacts that slide throughout follow Walton's model exactly: the tangential impulse
/// is μ times the normal one, (1 + ε) m_eff g_n, so β = −1 + μ (1 + ε)(1 + 1/q) g_n/g_t
/// with the contact's own ε, for an instantaneous contact. A contact of finite duration
/// turns the line of centres (by ~g_t t_c / σ: printed), which moves the decomposition at
/// that order: a material 1e7 times stiffer than the others keeps the turn below 2e-3 and
/// the bound 5e-3 on β holds it.
#[test]
fn sliding_contacts_follow_walton() {
    // A 1e7 times stiffer material whose damping gives the same eps: β_v ∝ A ρ^{2/5}.
    let m = ViscoelasticMaterial::new(1e12, 0.3, 2e-3 * 1e-7f64.powf(0.4)).unwrap();
    let q = 0.4;
    let dt = duration(&m) / 1000.0;
    for g_t in [2.0, 5.0, 20.0] {
        let mu = 0.1;
        let md = oblique_contact(m, mu, (RADIUS, MASS, q), (1.0, g_t), dt).unwrap();
        let walton = -1.0 + mu * (1.0 + md.eps) * (1.0 + 1.0 / q) / g_t;
        println!(
            "g_t/g_n = {g_t}: beta {:.6}, Walton {walton:.6}, eps {:.5}, turn {:.2e}",
            md.beta, md.eps, md.turn
        );
        assert!(md.slid);
        assert!(md.turn.abs() < 2e-3);
        assert!((md.beta - walton).abs() < 5e-3, "{} vs {walton}", md.beta);
    }
}

/// A dense rough gas: N spheres near contact, thermal velocities and spins.
fn rough_gas(friction: f64, dt_fraction: f64) -> SoftSphere<3> {
    // Apart (no overlaps to start with: a start deep in overlap is not resolved by a step
    // made for the contacts of the gas's speeds).
    let (n_side, spacing) = (5usize, 1.2);
    let length = n_side as f64 * spacing;
    // A Weyl sequence through the Box–Muller map: any deterministic spread will do.
    let mut k = 0u64;
    let mut uniform = move || {
        k += 1;
        ((k as f64) * 0.618_033_988_749_895).fract().max(1e-12)
    };
    let mut normal =
        move || (-2.0 * uniform().ln()).sqrt() * (std::f64::consts::TAU * uniform()).cos();
    let n = n_side.pow(3);
    let positions = (0..n)
        .map(|p| {
            let c = [p % n_side, (p / n_side) % n_side, p / (n_side * n_side)];
            std::array::from_fn(|k| (c[k] as f64 + 0.5) * spacing + 0.05 * normal())
        })
        .collect();
    let velocities = (0..n).map(|_| std::array::from_fn(|_| normal())).collect();
    let system = System {
        sides: [length; 3],
        positions,
        velocities,
        radii: vec![RADIUS; n],
        masses: vec![MASS; n],
    };
    let m = material(2e-3);
    let options = SoftSphereOptions {
        time_step: Some(duration(&m) * dt_fraction),
        ..Default::default()
    };
    let mut engine = SoftSphere::new(system.clone(), m, options).unwrap();
    engine.set_friction(Some(friction)).unwrap();
    let rotation = Rotation::thermal(&system, vec![0.4; n], 1.0, 3);
    engine.set_rotation(Some(rotation)).unwrap();
    engine
}

/// Kinetic energy of translation and rotation.
fn kinetic(engine: &mut SoftSphere<3>) -> f64 {
    let s = Engine::system(engine).clone();
    let translation: f64 = (0..s.len())
        .map(|i| 0.5 * s.masses[i] * dot(&s.velocities[i], &s.velocities[i]))
        .sum();
    translation + Engine::rotation(engine).unwrap().energy(&s)
}

/// Kinetic + elastic (normal overlaps and tangential springs) + energy lost stays what it
/// was to the accuracy of the step, and that error converges at second order: halving
/// the step divides the residual after the same time (some 30 contact durations) by about
/// 4 (asserted > 2.5, allowing the chaotic gas's trajectories to part a little between
/// the two steps).
#[test]
fn the_energy_balance_converges_at_second_order() {
    let residual = |fraction: f64| {
        let mut engine = rough_gas(0.5, fraction);
        let start = kinetic(&mut engine) + engine.elastic_energy();
        let steps = (32.0 / fraction) as u64;
        engine.run_steps(steps);
        let now = kinetic(&mut engine) + engine.elastic_energy() + engine.counters().energy_lost;
        assert!(engine.counters().energy_lost > 1e-3 * start);
        assert!(Engine::rotation(&mut engine).unwrap().sliding > 0);
        (now - start).abs() / start
    };
    let (coarse, fine) = (residual(1.0 / 40.0), residual(1.0 / 80.0));
    println!("relative residual: {coarse:.3e} at t_c/40, {fine:.3e} at t_c/80");
    assert!(coarse / fine > 2.5, "{coarse} / {fine}");
}

/// Total angular momentum Σ m x × v + I ω of two spheres (away from the box's faces) is
/// kept through an oblique, partly sliding contact to round-off: the torques' arms add
/// up to the distance of the centres.
#[test]
fn angular_momentum_is_kept() {
    let m = material(2e-3);
    let length = 16.0;
    let system = System {
        sides: [length; 3],
        positions: vec![[7.5, 8.0, 8.0], [8.5 - 1e-3, 8.3, 8.1]],
        velocities: vec![[0.5, 0.2, -0.1], [-0.5, -0.3, 0.4]],
        radii: vec![RADIUS; 2],
        masses: vec![MASS; 2],
    };
    let options = SoftSphereOptions {
        time_step: Some(duration(&m) / 200.0),
        ..Default::default()
    };
    let mut engine = SoftSphere::<3>::new(system, m, options).unwrap();
    engine.set_friction(Some(0.3)).unwrap();
    let mut rotation = Rotation::at_rest(2, 0.4);
    rotation.angular = vec![[1.0, -2.0, 0.5], [0.0, 3.0, -1.0]];
    engine.set_rotation(Some(rotation)).unwrap();
    let momentum = |engine: &mut SoftSphere<3>| {
        let w = Engine::rotation(engine).unwrap().angular.clone();
        let s = Engine::system(engine);
        let mut l = [0.0; 3];
        for (i, spin) in w.iter().enumerate() {
            let orbital = cross(&s.positions[i], &s.velocities[i]);
            for k in 0..3 {
                l[k] += s.masses[i] * orbital[k] + 0.4 * MASS * RADIUS * RADIUS * spin[k];
            }
        }
        l
    };
    let before = momentum(&mut engine);
    let mut touched = false;
    for _ in 0..2000 {
        engine.run_steps(1);
        touched |= !engine.contacts().is_empty();
    }
    assert!(touched && engine.contacts().is_empty());
    let after = momentum(&mut engine);
    for k in 0..3 {
        assert!(
            (after[k] - before[k]).abs() < 1e-12 * 16.0,
            "{before:?} {after:?}"
        );
    }
}

/// Friction 0: the tangential force vanishes, translation runs bit for bit as for smooth
/// spheres and the spins stay as they were.
#[test]
fn zero_friction_is_smooth() {
    let mut rough = rough_gas(0.0, 1.0 / 50.0);
    let mut smooth = rough_gas(0.0, 1.0 / 50.0);
    smooth.set_rotation(None).unwrap();
    let spins = Engine::rotation(&mut rough).unwrap().angular.clone();
    rough.run_steps(200);
    smooth.run_steps(200);
    assert_eq!(Engine::system(&mut rough), Engine::system(&mut smooth));
    assert_eq!(Engine::rotation(&mut rough).unwrap().angular, spins);
    assert_eq!(rough.counters().collisions, smooth.counters().collisions);
}

/// A rough gas saved mid-run and restored continues bit for bit, through the state's
/// postcard bytes (the springs of the contacts then open, the torques, the spins).
#[test]
fn check_points_resume_bit_for_bit() {
    let mut first = rough_gas(0.5, 1.0 / 50.0);
    first.run_steps(300);
    let mut steps = 300;
    while first.contacts().is_empty() || Engine::rotation(&mut first).unwrap().sliding == 0 {
        first.run_steps(1);
        steps += 1;
    }
    let mut straight = rough_gas(0.5, 1.0 / 50.0);
    straight.run_steps(steps + 200);
    let mut bytes = postcard::to_stdvec(&first.save()).unwrap();
    bytes.extend([0; gas::tail::TAIL_PADDING]);
    let state = postcard::from_bytes(&bytes).unwrap();
    let mut resumed = SoftSphere::<3>::restore(state, ()).unwrap();
    resumed.run_steps(200);
    assert_eq!(Engine::system(&mut resumed), Engine::system(&mut straight));
    assert_eq!(
        Engine::rotation(&mut resumed),
        Engine::rotation(&mut straight)
    );
    assert_eq!(resumed.counters(), straight.counters());
    assert_eq!(resumed.elastic_energy(), straight.elastic_energy());
}

/// Bad input names the key: negative or non-finite friction, a rotation without friction,
/// a state whose springs do not match its contacts.
#[test]
fn bad_input_names_the_key() {
    let mut engine = rough_gas(0.5, 1.0 / 50.0);
    for mu in [-0.1, f64::NAN, f64::INFINITY] {
        let e = engine.set_friction(Some(mu)).unwrap_err().to_string();
        assert!(e.contains("friction"), "{e}");
    }
    assert!(engine
        .set_friction(None)
        .unwrap_err()
        .to_string()
        .contains("friction"));
    let m = material(2e-3);
    let system = Engine::system(&mut engine).clone();
    let mut smooth = SoftSphere::new(system.clone(), m, SoftSphereOptions::default()).unwrap();
    let e = smooth
        .set_rotation(Some(Rotation::at_rest(system.len(), 0.4)))
        .unwrap_err()
        .to_string();
    assert!(e.contains("friction"), "{e}");
    while engine.contacts().is_empty() {
        engine.run_steps(1);
    }
    let mut state = engine.save();
    state
        .tail
        .history
        .as_mut()
        .unwrap()
        .springs
        .push(Default::default());
    let e = SoftSphere::<3>::restore(state, ())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("springs"), "{e}");
}

/// The table of docs/rough.md ("Soft spheres against Walton's model"): the effective β of
/// oblique contacts against g_t/g_n for μ = 0.1 and 0.3 (q = 0.4, ε ≈ 0.75), with Walton's
/// two-regime model of the same sticking β₀ (the engine's at g_t/g_n = 0.01) and ε.
/// `cargo test --release -p haff-gas --test soft_rough walton_table -- --ignored --nocapture`
#[test]
#[ignore]
fn walton_table() {
    let m = ViscoelasticMaterial::new(1e12, 0.3, 2e-3 * 1e-7f64.powf(0.4)).unwrap();
    let q = 0.4;
    let dt = duration(&m) / 2000.0;
    let sticking = oblique_contact(m, 1e9, (RADIUS, MASS, q), (1.0, 0.01), dt).unwrap();
    println!(
        "sticking beta0 = {:.4}, eps = {:.4}",
        sticking.beta, sticking.eps
    );
    println!("| g_t/g_n | μ | β (MD) | β (Walton) | slid (MD) |");
    println!("|---|---|---|---|---|");
    for mu in [0.1, 0.3] {
        for psi in [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0] {
            let md = oblique_contact(m, mu, (RADIUS, MASS, q), (1.0, psi), dt).unwrap();
            let walton = (-1.0 + mu * (1.0 + md.eps) * (1.0 + 1.0 / q) / psi).min(sticking.beta);
            println!(
                "| {psi} | {mu} | {:.4} | {walton:.4} | {} |",
                md.beta,
                if md.slid { "yes" } else { "no" }
            );
        }
    }
}
