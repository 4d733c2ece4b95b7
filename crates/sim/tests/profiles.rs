//! `[output] profiles`: slabs along an axis, against equilibrium between thermal walls,
//! the particle count, check-points, `profiles.csv` and the refusals of bad keys.

use sim::profiles::ProfileRow;
use sim::{Point, Simulation};

const THERMAL: &str = "[system]\ndimension = 2\nparticles = 400\npacking_fraction = 0.1\nseed = 11\ntemperature = 1.5\n\
     [collision]\nlaw = \"constant\"\nrestitution = 1.0\n\
     [run]\ncollisions_per_particle = 1000\nsamples = 201\nspacing = \"linear\"\n\
     [output]\nprofiles = { axis = \"y\", bins = 32 }\n\
     [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"thermal\"\ntemperature = 1.5\n\
     [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"thermal\"\ntemperature = 1.5\n";

/// Oracle: an elastic gas between two Maxwell walls at T_w is in equilibrium at T_w, in
/// every slab (detailed balance of the diffuse wall). 32 slabs of ~12 particles make the
/// estimator's n − 1 matter: with n instead the slabs would read T_w (1 − 1/12), 8 % low,
/// ~8 standard errors. The gas's energy exchanged with the walls decorrelates only in a
/// heat-diffusion time (~50 collisions per particle), so errors are batch means: 10
/// batches of the slab-averaged temperature, 4 errors overall, 6 per slab (t with 9
/// degrees of freedom: 2e-4 each).
#[test]
fn slabs_between_thermal_walls_are_at_the_walls_temperature() {
    let mut run = Simulation::from_toml(THERMAL, "thermal.toml".as_ref()).unwrap();
    run.run(&mut (), None).unwrap();
    let rows = run.profile_rows().unwrap();
    assert_eq!(rows.len(), 201 * 32);
    let volume = 400.0 * std::f64::consts::PI * 0.25 / 0.1;
    for sample in rows.chunks(32) {
        // Every particle in one slab: Σ density × slab volume = N.
        let count: f64 = sample.iter().map(|r| r.density * volume / 32.0).sum();
        assert!((count - 400.0).abs() < 1e-9, "{count}");
        let phi: f64 = sample.iter().map(|r| r.packing_fraction).sum::<f64>() / 32.0;
        assert!((phi - 0.1).abs() < 1e-12, "{phi}");
        assert!(sample.windows(2).all(|w| w[1].position > w[0].position));
        assert!(sample.iter().all(|r| r.velocity_component(2).is_none()));
    }
    // Started in equilibrium at T_w (Maxwellian velocities, uniform positions); the first
    // 10 collisions per particle melt the start's positions.
    let settled: Vec<&[ProfileRow]> = rows
        .chunks(32)
        .filter(|s| s[0].collisions_per_particle >= 10.0)
        .collect();
    let slab_mean = |rows: &[&[ProfileRow]], slab: Option<usize>| {
        let values: Vec<f64> = rows
            .iter()
            .flat_map(|s| s.iter().enumerate())
            .filter(|(k, _)| slab.is_none_or(|j| j == *k))
            .filter_map(|(_, r)| r.temperature)
            .collect();
        values.iter().sum::<f64>() / values.len() as f64
    };
    let (mean, error) = batch_means(&settled, |batch| slab_mean(batch, None));
    eprintln!("slab temperature {mean} ± {error} (T_w = 1.5)");
    assert!((mean - 1.5).abs() < 4.0 * error, "{mean} ± {error}");
    // Small enough that the n-estimator's 8 % would fail by 4 errors.
    assert!(error < 0.03, "{error}");
    for slab in 0..32 {
        let (mean, error) = batch_means(&settled, |batch| slab_mean(batch, Some(slab)));
        assert!(
            (mean - 1.5).abs() < 6.0 * error,
            "slab {slab}: {mean} ± {error}"
        );
    }
}

/// The mean of `f` over 10 contiguous batches of `samples`, and its standard error.
fn batch_means(samples: &[&[ProfileRow]], f: impl Fn(&[&[ProfileRow]]) -> f64) -> (f64, f64) {
    let values: Vec<f64> = samples.chunks(samples.len() / 10).take(10).map(f).collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (variance / n).sqrt())
}

/// A check-point taken mid-run resumes the profiles bit for bit; `profiles.csv` has the
/// issue's header and leaves the components a 2D gas lacks empty.
#[test]
fn profiles_are_resumed_and_written() {
    let text = THERMAL
        .replace(
            "collisions_per_particle = 1000",
            "collisions_per_particle = 20",
        )
        .replace("samples = 201", "samples = 61");
    let mut run = Simulation::from_toml(&text, "thermal.toml".as_ref()).unwrap();
    assert!(run
        .advance(Point::CollisionsPerParticle(7.0), &mut ())
        .unwrap());
    let dir = std::env::temp_dir().join(format!("haff-profiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("profiles.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.profile_rows(), run.profile_rows());
    loaded.write(&dir).unwrap();
    let csv = std::fs::read_to_string(dir.join("profiles.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time,collisions_per_particle,position,density,packing_fraction,temperature,\
         temperature_x,temperature_y,temperature_z,velocity_x,velocity_y,velocity_z"
    );
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(first.len(), 12);
    assert_eq!((first[8], first[11]), ("", ""));
    assert!(first[6].parse::<f64>().unwrap() > 0.0);
    assert_eq!(csv.lines().count(), 1 + 61 * 32);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Bad profiles: exit 2 (an input error) naming the key.
#[test]
fn bad_profiles_name_their_key() {
    let cases = [
        (
            "axis = \"y\", bins = 32",
            "axis = \"z\", bins = 32",
            "output.profiles.axis",
        ),
        (
            "axis = \"y\", bins = 32",
            "axis = \"y\", bins = 0",
            "output.profiles.bins",
        ),
        ("axis = \"y\", bins = 32", "axis = \"y\"", "bins"),
        (
            "axis = \"y\", bins = 32",
            "axis = \"y\", bins = 4, width = 2",
            "width",
        ),
        ("axis = \"y\", bins = 32", "axis = \"w\", bins = 4", "axis"),
        (
            "[run]\n",
            "[run]\nengine = \"dsmc\"\ndsmc_scheme = \"exact\"\n",
            "output.profiles",
        ),
    ];
    let periodic = THERMAL.split("[[wall]]").next().unwrap();
    for (from, to, key) in cases {
        let text = periodic.replace(from, to);
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"));
        assert!(error.is_input(), "{error}");
        assert!(error.to_string().contains(key), "{key}: {error}");
    }
}
