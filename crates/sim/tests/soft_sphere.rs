//! `run.engine = "soft-sphere"` from a run file: the material keys, the errors that name
//! them, check-points, and the same gas as eMD with the exact coefficient of restitution.

use sim::{Error, Simulation};

/// A dilute viscoelastic gas (3D, phi = 0.02; units sigma = m = T0 = 1). Y = 1e5 and
/// A = 0.01 give beta = 0.44 (v* ~ 0.7 at the thermal speed: eps ~ 0.6), so the gas cools by
/// ~10 in 20 time units, while a contact lasts ~0.05 of the free time.
fn gas(engine: &str, particles: usize, end_time: f64) -> String {
    format!(
        "[system]\ndimension = 3\nparticles = {particles}\npacking_fraction = 0.02\nseed = 3\n\
         [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\n\
         dissipative_constant = 0.01\nform = \"exact\"\n\
         [run]\nengine = \"{engine}\"\nend_time = {end_time}\nsamples = 5\nspacing = \"linear\"\n"
    )
}

fn refused_key(toml: &str) -> String {
    match Simulation::from_toml(toml, "bad.toml".as_ref()) {
        Err(Error::Input { key, .. }) => key,
        Err(other) => panic!("{toml}: not an input error: {other}"),
        Ok(_) => panic!("{toml}: accepted"),
    }
}

#[test]
fn material_keys_are_checked_and_named() {
    let good = gas("soft-sphere", 100, 1.0).replace("form = \"exact\"\n", "");
    assert!(Simulation::from_toml(&good, "g.toml".as_ref()).is_ok());
    for (from, to, key) in [
        ("young = 1e5\n", "", "collision.young"),
        ("poisson = 0.3", "poisson = 0.5", "collision.poisson"),
        (
            "dissipative_constant = 0.01",
            "dissipative_constant = -1.0",
            "collision.dissipative_constant",
        ),
        ("young = 1e5", "young = 1e5\nbeta = 0.1", "collision.beta"),
        (
            "law = \"viscoelastic\"",
            "law = \"constant\"\nrestitution = 0.9",
            "collision.young",
        ),
        (
            "end_time = 1",
            "end_time = 1\nsteps_per_contact = 2.0",
            "run.steps_per_contact",
        ),
        (
            "end_time = 1",
            "end_time = 1\nblock_size = 64",
            "run.block_size",
        ),
        (
            "end_time = 1",
            "end_time = 1\nsteps_per_contact = 20.0\ntime_step = 0.1",
            "run.time_step",
        ),
        // The contact lasts ~0.017 at ten thermal speeds: 0.1 misses contacts, 1e-12 would
        // take 1e12 steps.
        (
            "end_time = 1",
            "end_time = 1\ntime_step = 0.1",
            "run.time_step",
        ),
        (
            "end_time = 1",
            "end_time = 1\ntime_step = 1e-12",
            "run.time_step",
        ),
        // So stiff in the run's units that the run would take more than 1e8 steps.
        ("young = 1e5", "young = 1e25", "run.end_time"),
        (
            "end_time = 1",
            "collisions_per_particle = 1e6",
            "run.collisions_per_particle",
        ),
    ] {
        assert!(good.contains(from), "{from}");
        assert_eq!(refused_key(&good.replacen(from, to, 1)), key, "{to}");
    }
    // The force needs the material: beta alone is not enough.
    let beta_only = good.replace(
        "young = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n",
        "beta = 0.4\n",
    );
    assert_eq!(refused_key(&beta_only), "collision.law");
    // Strong damping (A = 3: v* ~ 25 at ten thermal speeds) with 4 steps per contact: the
    // explicit scheme overshoots the damping; the probe of isolated contacts finds eps off
    // by ~9 and the run is refused, naming the key that set the step.
    let overdamped = good.replace("dissipative_constant = 0.01", "dissipative_constant = 3.0");
    assert_eq!(
        refused_key(&overdamped.replace("end_time = 1", "end_time = 1\nsteps_per_contact = 4")),
        "run.steps_per_contact"
    );
    assert!(Simulation::from_toml(&overdamped, "g.toml".as_ref()).is_ok());
    // A step within 4 ..= 1e6 steps per contact is taken as given.
    let fixed = good.replace("end_time = 1", "end_time = 1\ntime_step = 1e-3");
    assert!(Simulation::from_toml(&fixed, "g.toml".as_ref()).is_ok());
    // steps_per_contact belongs to the soft-sphere engine.
    let emd = gas("event-driven", 100, 1.0) + "steps_per_contact = 50.0\n";
    assert_eq!(refused_key(&emd), "run.steps_per_contact");
}

/// A run stopped and resumed from its check-point ends bit for bit where the uninterrupted
/// run does.
#[test]
fn resumed_soft_sphere_run_is_bit_identical() {
    let text = gas("soft-sphere", 200, 4.0);
    let dir = std::env::temp_dir().join(format!("haff-soft-resume-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for part in ["whole", "parts"] {
        std::fs::create_dir_all(dir.join(part)).unwrap();
    }
    let mut whole = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    whole.set_checkpoints(&dir.join("whole"), Some(1));
    whole.run(&mut (), None).unwrap();
    let mut first = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    first.set_checkpoints(&dir.join("parts"), Some(1));
    first.run(&mut (), Some(2)).unwrap();
    let mut rest = Simulation::resume(&dir.join("parts")).unwrap();
    rest.run(&mut (), None).unwrap();
    assert_eq!(whole.samples(), rest.samples());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same gas by soft-sphere MD and by eMD with the exact law (beta from the same
/// material): T after cooling by ~4 (t = 10) agrees. The two runs of one seed decorrelate
/// (chaos); their ratio scatters by 2.4 % from seed to seed at this cooling (measured, 10
/// seeds, N = 2000, docs/soft-sphere.md), and soft-sphere MD is warmer by ~1-2 % (the
/// collision delay); tolerance 7 %, about 3 sigma from that offset, well below the
/// difference a wrong beta or force would make (beta x 2: ~30 % in T).
#[test]
fn soft_sphere_md_cools_like_emd_with_the_exact_law() {
    let t = |engine: &str| {
        let mut run = Simulation::from_toml(&gas(engine, 2000, 10.0), "t.toml".as_ref()).unwrap();
        run.run(&mut (), None).unwrap();
        run.samples().last().unwrap().temperature
    };
    let (md, emd) = (t("soft-sphere"), t("event-driven"));
    assert!(emd < 0.5, "the gas cools: T = {emd}");
    assert!(
        (md / emd - 1.0).abs() < 0.07,
        "soft-sphere T = {md}, eMD {emd}"
    );
}

/// summary.json of a soft-sphere run reports its contacts; an eMD run's has none. The time
/// step is recomputed here from the contact duration t_c = tau_c(v*) (m_eff / rho)^(2/5)
/// v^(-1/5) at ten thermal speeds (v = 10 sqrt(T/m) = 10; v* = beta^(1/2) v^(1/10), tau_c
/// the scaled duration of Eq. (9) of MP2011) over the default 50 steps per contact.
#[test]
fn summary_reports_the_contacts_of_soft_sphere_runs() {
    let dir = std::env::temp_dir().join(format!("haff-soft-summary-{}", std::process::id()));
    let summary = |engine: &str| {
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut run = Simulation::from_toml(&gas(engine, 300, 4.0), "t.toml".as_ref()).unwrap();
        run.run(&mut (), None).unwrap();
        run.write(&dir).unwrap();
        let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()
    };
    assert!(summary("event-driven").get("contacts").is_none());
    let s = summary("soft-sphere");
    let _ = std::fs::remove_dir_all(&dir);
    let c = &s["contacts"];
    let rho = 2.0 * 1e5 * 0.25f64.sqrt() / (3.0 * (1.0 - 0.09));
    let beta = 1.5 * 0.01 * (rho / 0.5f64).powf(0.4);
    let vstar = beta.sqrt() * 10f64.powf(0.1);
    let tau = restitution::exact::solve(vstar, restitution::exact::Criterion::Improved)
        .unwrap()
        .duration;
    let time_step = tau * (0.5 / rho).powf(0.4) * 10f64.powf(-0.2) / 50.0;
    let number = |key: &str| c[key].as_f64().unwrap_or_else(|| panic!("{key}: {c}"));
    assert!((number("time_step") / time_step - 1.0).abs() < 1e-12, "{c}");
    // 4 time units in steps of dt, the step before each of the 5 sample times shortened
    // to end on it.
    let whole = (4.0 / time_step).ceil();
    assert!((whole..=whole + 4.0).contains(&number("steps")), "{c}");
    let (touching, multi) = (number("contact_steps"), number("multi_contact_steps"));
    assert!(touching > 0.0 && multi <= touching, "{c}");
    assert_eq!(number("multi_contact_fraction"), multi / touching);
    // The largest overlap stays below that of a head-on elastic contact at 10 thermal
    // relative speeds, xi_max = (5 m_eff v^2 / (4 rho))^(2/5), v = 10 sqrt(2).
    let xi_max = (5.0 * 0.5 * 200.0 / (4.0 * rho)).powf(0.4);
    assert!(
        (0.0..xi_max).contains(&number("max_relative_overlap")),
        "{c}"
    );
    assert!(number("elastic_energy") >= 0.0);
    // The engine's probe of isolated contacts (gas tests: below 1e-3 at 50 steps).
    assert!((0.0..1e-3).contains(&number("eps_error")), "{c}");
    assert_eq!(
        number("contacts_now") == 0.0,
        number("elastic_energy") == 0.0
    );
}

/// Soda-lime glass spheres in SI (d = 2 mm, sqrt(T/m) = 1 m/s, A = 1e-9 s), the material
/// given by its keys or by name.
fn glass(collision: &str, mass: &str) -> String {
    format!(
        "[system]\ndimension = 3\nparticles = 200\npacking_fraction = 0.05\ndiameter = 2e-3\n\
         {mass}temperature = 1.0471975511965977e-5\nseed = 1\n\
         [collision]\nlaw = \"viscoelastic\"\n{collision}dissipative_constant = 1e-9\n\
         [run]\nengine = \"soft-sphere\"\nend_time = 2e-3\nsamples = 4\n"
    )
}

/// `material = "soda-lime-glass"` is the table's Y = 72 GPa, nu = 0.23 and the mass of a
/// 2 mm sphere of density 2500 kg/m^3, 2500 pi (2e-3)^3 / 6 = 1.0471975511965977e-5 kg:
/// the run equals the one with those keys (the same events; T and the energy lost to
/// 1e-12, as the two masses may differ in the last bit). Errors name the key.
#[test]
fn a_named_material_gives_young_poisson_and_the_mass() {
    let samples = |text: &str| {
        let mut run = Simulation::from_toml(text, "g.toml".as_ref()).unwrap();
        run.run(&mut (), None).unwrap();
        run.samples().to_vec()
    };
    let mass = "mass = 1.0471975511965977e-5\n";
    let explicit = glass("young = 72e9\npoisson = 0.23\n", mass);
    let named = glass("material = \"soda-lime-glass\"\n", "");
    let by_keys = samples(&explicit);
    assert!(by_keys.last().unwrap().collisions_per_particle > 0.5);
    let same = |other: &[sim::observer::Sample]| {
        assert_eq!(other.len(), by_keys.len());
        for (a, b) in by_keys.iter().zip(other) {
            assert_eq!((a.time, a.events), (b.time, b.events));
            assert!(
                (a.temperature / b.temperature - 1.0).abs() < 1e-12,
                "{a:?} {b:?}"
            );
            assert!((a.energy_lost - b.energy_lost).abs() <= 1e-12 * a.temperature);
        }
    };
    same(&samples(&named));
    // With the mass given (matching), and with an explicit key overriding the table.
    same(&samples(&glass("material = \"Soda_Lime_Glass\"\n", mass)));
    let softer = glass("material = \"soda-lime-glass\"\nyoung = 36e9\n", "");
    assert_ne!(by_keys, samples(&softer));
    for (text, key) in [
        (
            glass("material = \"unobtainium\"\n", ""),
            "collision.material",
        ),
        (
            glass("material = \"ice\"\n", "").replace("dimension = 3", "dimension = 2"),
            "collision.material",
        ),
        (
            glass("material = \"ice\"\n", "").replace("viscoelastic", "constant"),
            "collision.material",
        ),
        (glass("material = \"ice\"\n", mass), "system.mass"),
        (
            glass("material = \"ice\"\n", "").replace("dissipative_constant = 1e-9\n", ""),
            "collision.dissipative_constant",
        ),
    ] {
        assert_eq!(refused_key(&text), key, "{text}");
    }
}
