//! Viscoelastic mixtures: species of their own materials (`system.species[i].young`,
//! `poisson`, `dissipative_constant`) collide with the beta of their pair, checked against
//! the law of the pair's constants written out here, through a two-particle event-driven
//! collision; and the keys are checked.

use gas::emd::EventDriven;
use gas::{Engine, System};
use restitution::{Restitution, Viscoelastic};
use sim::{RunDescription, Simulation};
use std::path::Path;

/// Two species of unlike materials (Y, nu, A) and sizes: (diameter, mass, material).
const SPECIES: [(f64, f64, (f64, f64, f64)); 2] =
    [(1.0, 1.0, (1e5, 0.3, 1e-3)), (1.4, 2.744, (1e4, 0.4, 5e-3))];

fn run_file(species_keys: [&str; 2], collision_keys: &str, engine: &str) -> String {
    let list: Vec<String> = SPECIES
        .iter()
        .zip(species_keys)
        .map(|((d, m, _), keys)| format!("{{ diameter = {d}, mass = {m}, fraction = 0.5{keys} }}"))
        .collect();
    format!(
        "[system]\ndimension = 3\nparticles = 100\npacking_fraction = 0.05\nspecies = [{}]\n\
         [collision]\nlaw = \"viscoelastic\"\nform = \"exact\"\n{collision_keys}\n[run]\n\
         engine = \"{engine}\"\ncollisions_per_particle = 1\nsamples = 2\n",
        list.join(", ")
    )
}

fn material_keys((y, nu, a): (f64, f64, f64)) -> String {
    format!(", young = {y:e}, poisson = {nu}, dissipative_constant = {a:e}")
}

/// beta of spheres i and j written out from the contact mechanics (not the code's
/// functions): compliances D = (1 - nu^2)/Y add, rho = (4/3) sqrt(R_eff) / (D_i + D_j),
/// A_ij = (A_i D_i + A_j D_j) / (D_i + D_j), beta = (3/2) A_ij (rho / m_eff)^(2/5).
fn pair_beta(i: usize, j: usize) -> f64 {
    let (di, mi, (yi, ni, ai)) = SPECIES[i];
    let (dj, mj, (yj, nj, aj)) = SPECIES[j];
    let (ci, cj) = ((1.0 - ni * ni) / yi, (1.0 - nj * nj) / yj);
    let r_eff = (di / 2.0) * (dj / 2.0) / (di / 2.0 + dj / 2.0);
    let rho = 4.0 / 3.0 * r_eff.sqrt() / (ci + cj);
    let a = (ai * ci + aj * cj) / (ci + cj);
    1.5 * a * (rho / (mi * mj / (mi + mj))).powf(0.4)
}

/// Each pair's law is the exact viscoelastic law at the pair's beta: the like pairs at the
/// textbook rho = 2 Y sqrt(R_eff) / (3 (1 - nu^2)) of one material, the unlike pair at the
/// mixed constants; and two unlike spheres meeting head-on in the event-driven engine
/// leave at eps(v) of that law.
#[test]
fn species_materials_collide_with_their_pair_s_beta() {
    let text = run_file(
        [&material_keys(SPECIES[0].2), &material_keys(SPECIES[1].2)],
        "",
        "event-driven",
    );
    let d = RunDescription::from_toml(&text, Path::new("v.toml")).unwrap();
    let plan = sim::validate(&d).unwrap();
    let law = sim::law::build(&plan.law, plan.max_impact_speed()).unwrap();
    let table = law.pairwise().expect("a law per pair");
    let exact = |beta: f64| Viscoelastic::new(beta, "exact".parse().unwrap()).unwrap();
    for (i, (d, m, (y, nu, a))) in SPECIES.iter().enumerate() {
        let rho = 2.0 * y * (d / 4.0).sqrt() / (3.0 * (1.0 - nu * nu));
        let like = 1.5 * a * (rho / (m / 2.0)).powf(0.4);
        assert!((like / pair_beta(i, i) - 1.0).abs() < 1e-13);
        for v in [0.1, 1.0, 5.0] {
            let (got, want) = (table.law(i, i).eps(v), exact(like).eps(v));
            assert!((got - want).abs() < 1e-13, "{i}{i} at {v}: {got} vs {want}");
        }
    }
    let unlike = pair_beta(0, 1);
    // The soft species dominates: beta_01 lies well away from both like betas.
    assert!(unlike != pair_beta(0, 0) && unlike != pair_beta(1, 1));
    // Head-on at relative speed 2 in the event-driven engine.
    let system = System::<3> {
        sides: [20.0; 3],
        positions: vec![[5.0, 10.0, 10.0], [8.0, 10.0, 10.0]],
        velocities: vec![[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]],
        radii: vec![SPECIES[0].0 / 2.0, SPECIES[1].0 / 2.0],
        masses: vec![SPECIES[0].1, SPECIES[1].1],
    };
    let mut engine = EventDriven::new(system, law.box_clone()).unwrap();
    engine.run_collisions(1);
    let v = &engine.system().velocities;
    let eps = (v[1][0] - v[0][0]) / 2.0;
    let want = exact(unlike).eps(2.0);
    assert!(want < 0.97, "a dissipative collision: {want}");
    assert!((eps - want).abs() < 1e-12, "{eps} vs {want}");
}

/// One material for every species (`[collision]`): beta per pair from the pair's radii and
/// masses; a species key overrides the collision's.
#[test]
fn a_shared_material_gives_each_pair_its_beta() {
    let (y, nu, a) = SPECIES[0].2;
    let collision = format!("young = {y:e}\npoisson = {nu}\ndissipative_constant = {a:e}");
    let plan = |species_keys: [&str; 2]| {
        let text = run_file(species_keys, &collision, "dsmc");
        sim::validate(&RunDescription::from_toml(&text, Path::new("v.toml")).unwrap()).unwrap()
    };
    let shared = plan(["", ""]);
    let sim::validate::LawSpec::ViscoelasticPairs { betas, .. } = &shared.law else {
        panic!("{:?}", shared.law)
    };
    let material = gas::soft::contact::ViscoelasticMaterial::new(y, nu, a).unwrap();
    for (i, row) in betas.iter().enumerate() {
        for (j, beta) in row.iter().enumerate() {
            let (ri, rj) = (SPECIES[i].0 / 2.0, SPECIES[j].0 / 2.0);
            let want = material.beta(ri, rj, SPECIES[i].1, SPECIES[j].1);
            assert!((beta / want - 1.0).abs() < 1e-14);
        }
    }
    // Species 1 overrides A only: its pairs change, 0-0 does not.
    let overridden = plan(["", ", dissipative_constant = 5e-3"]);
    let sim::validate::LawSpec::ViscoelasticPairs { betas: other, .. } = &overridden.law else {
        panic!()
    };
    assert_eq!(other[0][0], betas[0][0]);
    assert!(other[1][1] > 4.9 * betas[1][1] && other[0][1] > betas[0][1]);
}

#[test]
fn species_materials_are_checked() {
    let error = |text: String| {
        let e = Simulation::from_toml(&text, Path::new("v.toml"))
            .err()
            .unwrap();
        assert!(e.is_input(), "{e}");
        e.to_string()
    };
    let full = material_keys(SPECIES[0].2);
    let cases = [
        // A species without the poisson ratio and none in [collision].
        (
            run_file(
                [&full, ", young = 1e4, dissipative_constant = 1e-3"],
                "",
                "dsmc",
            ),
            "system.species[1].poisson",
            "missing",
        ),
        (
            run_file(
                [
                    &full,
                    ", young = -1.0, poisson = 0.3, dissipative_constant = 0",
                ],
                "",
                "dsmc",
            ),
            "system.species[1].young",
            "Y > 0",
        ),
        (
            run_file([&full, &full], "beta = 0.1", "dsmc"),
            "collision.beta",
            "not both",
        ),
        (
            run_file([&full, &full], "", "soft-sphere"),
            "system.species[0].young",
            "one material",
        ),
        (
            run_file([&full, ""], "", "dsmc").replace(
                "law = \"viscoelastic\"\nform = \"exact\"",
                "law = \"constant\"\nrestitution = 0.9",
            ),
            "system.species[0].young",
            "law = \"viscoelastic\"",
        ),
    ];
    for (text, key, allowed) in cases {
        let e = error(text);
        assert!(e.contains(key) && e.contains(allowed), "{key}: {e}");
    }
}

/// A viscoelastic mixture of unlike materials cooling (3D, phi = 0.1, DSMC exact scheme,
/// N = 5e4, 300 collisions per particle, 10 decades of temperature): each species'
/// temperature follows the Maxwellian free cooling of kinetic theory with the pairs'
/// speed-dependent restitution (`MixtureTheory::free_cooling`) at every sample within
/// 3.5 standard errors sqrt(2 / (D N_i)) (the largest of 30 samples) plus the Maxwellian
/// approximation's error: on the power law T ~ (k t)^(-5/3) a relative error e of the
/// rate coefficient is (5/3) e in T, and the first Sonine correction of the rate is
/// (3/16) a2 (van Noije & Ernst), with |a2_i| <= 0.05 asserted in the run. The ratio
/// T1/T0 rises to the theory's peak (1.22, within 2 %) and falls back towards 1 as the
/// collisions turn elastic; the late slope d ln T / d ln t is the theory's within 0.02.
#[test]
fn a_viscoelastic_mixture_cools_as_kinetic_theory_says() {
    const MIX: [(f64, f64, (f64, f64, f64)); 2] =
        [(1.0, 1.0, (1e5, 0.3, 2e-3)), (1.4, 2.744, (1e4, 0.4, 1e-2))];
    let (particles, phi) = (50_000usize, 0.1);
    let list: Vec<String> = MIX
        .iter()
        .map(|(d, m, material)| {
            format!(
                "{{ diameter = {d}, mass = {m}, fraction = 0.5{} }}",
                material_keys(*material)
            )
        })
        .collect();
    let text = format!(
        "[system]\ndimension = 3\nparticles = {particles}\npacking_fraction = {phi}\nseed = 3\n\
         species = [{}]\n[collision]\nlaw = \"viscoelastic\"\n[run]\nengine = \"dsmc\"\n\
         dsmc_scheme = \"exact\"\ncollisions_per_particle = 300\nsamples = 30\n",
        list.join(", ")
    );
    let d = RunDescription::from_toml(&text, Path::new("v.toml")).unwrap();
    let plan = sim::validate(&d).unwrap();
    let law = sim::law::build(&plan.law, plan.max_impact_speed()).unwrap();
    let table = law.pairwise().unwrap().clone();
    let mut s = Simulation::new(&d).unwrap();
    s.run(&mut (), None).unwrap();
    let rows = s.species_samples().unwrap();
    let theory = gas::theory::MixtureTheory::<3>::new(
        &MIX.map(|x| x.1),
        &MIX.map(|x| x.0),
        &[0.5, 0.5],
        &[vec![1.0; 2], vec![1.0; 2]],
        phi,
    )
    .unwrap();
    let eps = |i: usize, j: usize, g: f64| table.law(i, j).eps(g);
    let times: Vec<f64> = rows.chunks(2).map(|p| p[0].time).collect();
    let initial = [rows[0].temperature, rows[1].temperature];
    let predicted = theory.free_cooling(&initial, &eps, &times, 50).unwrap();
    let first = rows.chunks(2).last().unwrap()[0].temperature / initial[0];
    assert!(first < 1e-9, "ten decades of cooling: {first:e}");
    let sigma = (2.0 / (3.0 * particles as f64 / 2.0)).sqrt();
    let tolerance = 3.5 * sigma + 5.0 / 3.0 * 3.0 / 16.0 * 0.05;
    for (p, q) in rows.chunks(2).zip(&predicted) {
        for k in 0..2 {
            assert!(p[k].a2.abs() <= 0.05, "a2 {} at t = {}", p[k].a2, p[k].time);
            let deviation = p[k].temperature / q[k] - 1.0;
            assert!(
                deviation.abs() < tolerance,
                "species {k} at t = {:e}: {:e} vs theory {:e}",
                p[k].time,
                p[k].temperature,
                q[k]
            );
        }
    }
    let measured: Vec<f64> = rows
        .chunks(2)
        .map(|p| p[1].temperature / p[0].temperature)
        .collect();
    let theory_ratio: Vec<f64> = predicted.iter().map(|q| q[1] / q[0]).collect();
    let peak = |r: &[f64]| r.iter().cloned().fold(0.0, f64::max);
    assert!((peak(&measured) / peak(&theory_ratio) - 1.0).abs() < 0.02);
    assert!(peak(&theory_ratio) > 1.2);
    let last = *measured.last().unwrap();
    assert!(last - 1.0 < (peak(&measured) - 1.0) / 3.0, "{last}");
    // Late slope, least squares over t > 1e3 (mixture temperature x_0 T_0 + x_1 T_1).
    let slope = |points: Vec<(f64, f64)>| {
        let n = points.len() as f64;
        let (mx, my) = points
            .iter()
            .fold((0.0, 0.0), |a, p| (a.0 + p.0 / n, a.1 + p.1 / n));
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
        sxy / sxx
    };
    let late = |t: &[f64]| -> Vec<(f64, f64)> {
        times
            .iter()
            .zip(t)
            .filter(|(time, _)| **time > 1e3)
            .map(|(time, temperature)| (time.ln(), temperature.ln()))
            .collect()
    };
    let mixture: Vec<f64> = rows
        .chunks(2)
        .map(|p| 0.5 * (p[0].temperature + p[1].temperature))
        .collect();
    let mixture_theory: Vec<f64> = predicted.iter().map(|q| 0.5 * (q[0] + q[1])).collect();
    let (got, want) = (slope(late(&mixture)), slope(late(&mixture_theory)));
    eprintln!(
        "late slope {got:.4} (theory {want:.4}); peak T1/T0 {:.4} (theory {:.4}); last {last:.4} \
         (theory {:.4})",
        peak(&measured),
        peak(&theory_ratio),
        theory_ratio.last().unwrap()
    );
    assert!((got - want).abs() < 0.02, "slope {got} vs theory {want}");
    assert!((want + 5.0 / 3.0).abs() < 0.1, "theory slope {want}");
}
