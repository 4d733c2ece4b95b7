//! Driven steady states in the engines that drive: white noise and the Gaussian thermostat
//! in the event-driven engine (at discrete times, every prediction renewed) and in DSMC,
//! against kinetic theory (the energy balance, van Noije & Ernst's a2, the HCS).

use gas::theory::MixtureTheory;
use sim::{RunDescription, Simulation};
use std::path::Path;

/// A monodisperse run's late samples (collisions per particle >= `from`): mean T, mean a2,
/// and the standard errors of both means from ten block means of consecutive samples.
fn steady(text: &str, from: f64) -> (f64, f64, f64, Simulation) {
    let (t, a2, (t_error, _), s) = steady_with_errors(text, from);
    (t, a2, t_error, s)
}

fn steady_with_errors(text: &str, from: f64) -> (f64, f64, (f64, f64), Simulation) {
    let d = RunDescription::from_toml(text, Path::new("driven.toml")).unwrap();
    let mut s = Simulation::new(&d).unwrap();
    s.run(&mut (), None).unwrap();
    let late: Vec<(f64, f64)> = s
        .samples()
        .iter()
        .filter(|x| x.collisions_per_particle >= from)
        .map(|x| (x.temperature, x.a2))
        .collect();
    let mean = |f: &dyn Fn(&(f64, f64)) -> f64, xs: &[(f64, f64)]| {
        xs.iter().map(f).sum::<f64>() / xs.len() as f64
    };
    let error = |f: &dyn Fn(&(f64, f64)) -> f64| {
        let blocks = 10;
        let means: Vec<f64> = late
            .chunks(late.len() / blocks)
            .take(blocks)
            .map(|c| mean(f, c))
            .collect();
        let m = means.iter().sum::<f64>() / blocks as f64;
        let var = means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (blocks as f64 - 1.0);
        (var / blocks as f64).sqrt()
    };
    let (t, a2) = (mean(&|x| x.0, &late), mean(&|x| x.1, &late));
    let errors = (error(&|x| x.0), error(&|x| x.1));
    (t, a2, errors, s)
}

fn monodisperse(phi: f64, n: usize, alpha: f64, driving: &str, run: &str) -> String {
    format!(
        "[system]\ndimension = 3\nparticles = {n}\npacking_fraction = {phi}\nseed = 3\n\
         [collision]\nlaw = \"constant\"\nrestitution = {alpha}\n[driving]\n{driving}\n\
         [run]\n{run}\nspacing = \"linear\"\n"
    )
}

/// White noise in the event-driven engine (3D, alpha = 0.8, xi^2 = 1, N = 4000, dilute:
/// phi = 0.01, where molecular chaos holds): the steady temperature is the first Sonine
/// energy balance (with the (1 - 1/N) of the momentum-free kicks) within 3 standard errors
/// of the mean (ten block means; ~0.35 %), at the default interval (a tenth of a mean free
/// time) and at one mean free time alike (the sawtooth of the temperature between kicks,
/// of relative size zeta dt, shifts the mean by ~(zeta dt)^2 / 48: 3e-4 at one mean free
/// time); a2 is negative, as van Noije & Ernst's -0.0087.
#[test]
fn event_driven_white_noise_reaches_the_energy_balance() {
    let (n, xi2, alpha, phi) = (4000usize, 1.0, 0.8, 0.01);
    let theory = MixtureTheory::<3>::new(&[1.0], &[1.0], &[1.0], &[vec![alpha]], phi).unwrap();
    let want = theory
        .white_noise(&[xi2 * (1.0 - 1.0 / n as f64)], true)
        .unwrap();
    let free_time = 1.0 / want.collision_frequencies[0];
    let mut found = Vec::new();
    for interval in ["".to_string(), format!("interval = {free_time}\n")] {
        let text = monodisperse(
            phi,
            n,
            alpha,
            &format!("kind = \"white-noise\"\nstrength = {xi2}\n{interval}"),
            "engine = \"event-driven\"\ncollisions_per_particle = 200\nsamples = 401",
        );
        let (t, a2, error, s) = steady(&text, 20.0);
        if interval.is_empty() {
            let chosen = s.plan().driving_interval.unwrap();
            assert!((chosen / free_time - 0.1).abs() < 0.01, "default {chosen}");
        }
        let target = want.temperatures[0];
        eprintln!("white noise, event-driven {interval:?}: T {t:.5} +- {error:.5} vs {target:.5}; a2 {a2:.4}");
        assert!(
            (t - target).abs() < 3.0 * error,
            "{interval}: T {t} +- {error} vs {target}"
        );
        assert!(a2 < 0.0, "a2 {a2}");
        found.push((t, error));
    }
    let ((t1, e1), (t2, e2)) = (found[0], found[1]);
    assert!((t1 - t2).abs() < 3.0 * (e1 * e1 + e2 * e2).sqrt());
}

/// The Gaussian thermostat in DSMC (3D, alpha = 0.8, N = 1e5, time step 0.02 mean free
/// times): the samples hold the target temperature (to rounding), the steady a2 is the
/// HCS's (first Sonine: van Noije & Ernst's -0.0126) within 25 % (the first Sonine
/// approximation's own error is ~10 % here; statistical error ~3 %), and the energy the
/// collisions take is the HCS cooling rate: within a step the gas cools by Haff's law,
/// T(t) = T* / (1 + zeta t / 2)^2, so a fraction f = 1 - 1/(1 + zeta dt / 2)^2 of the
/// energy goes per step, zeta = (2/dt)((1 - f)^(-1/2) - 1); it matches the first Sonine
/// rate zeta = (1 - alpha^2)(1 + 3 a2 / 16) omega / 3 within 0.5 % (the first Sonine
/// correction is 0.24 %; the statistical error of f is below 0.05 %).
#[test]
fn the_thermostat_holds_the_homogeneous_cooling_state() {
    let (n, alpha, phi, target) = (100_000usize, 0.8, 0.1, 2.0);
    let theory = MixtureTheory::<3>::new(&[1.0], &[1.0], &[1.0], &[vec![alpha]], phi).unwrap();
    let hcs = theory.hcs_sonine(target).unwrap();
    let omega = hcs.collision_frequencies[0];
    let dt = 0.02 / omega;
    let steps = 2000;
    let text = monodisperse(
        phi,
        n,
        alpha,
        &format!("kind = \"gaussian-thermostat\"\ntemperature = {target}"),
        &format!(
            "engine = \"dsmc\"\ntime_step = {dt}\nend_time = {}\nsamples = 101",
            steps as f64 * dt
        ),
    );
    let (t, a2, _, s) = steady(&text, 10.0);
    assert!((t / target - 1.0).abs() < 1e-12, "T {t}");
    let sonine = gas::theory::van_noije_ernst_a2::<3>(alpha);
    assert!((hcs.a2[0] / sonine - 1.0).abs() < 1e-6);
    assert!((a2 / sonine - 1.0).abs() < 0.25, "a2 {a2} vs {sonine}");
    let late: Vec<_> = s
        .samples()
        .iter()
        .filter(|x| x.collisions_per_particle >= 10.0)
        .collect();
    let (first, last) = (late[0], late[late.len() - 1]);
    let per_step = (last.energy_lost - first.energy_lost)
        / ((last.time - first.time) / dt)
        / (1.5 * n as f64 * target);
    let zeta = 2.0 / dt * ((1.0 - per_step).powf(-0.5) - 1.0);
    let want = hcs.cooling_rate;
    eprintln!("thermostat, DSMC: a2 {a2:.5} vs {sonine:.5}; zeta {zeta:.6} vs {want:.6}");
    assert!((zeta / want - 1.0).abs() < 0.005, "zeta {zeta} vs {want}");
}

/// The Gaussian thermostat in the event-driven engine (3D, alpha = 0.8, phi = 0.01,
/// N = 4000, default interval): between applications the gas cools by at most zeta dt
/// (1.2 %), so every sample lies in [T* (1 - 2 zeta dt), T*]; a2 is the HCS's (first
/// Sonine -0.0126) within 40 % (statistical error ~15 % at this N).
#[test]
fn the_thermostat_drives_the_event_driven_engine() {
    let (n, alpha, phi, target) = (4000usize, 0.8, 0.01, 1.0);
    let theory = MixtureTheory::<3>::new(&[1.0], &[1.0], &[1.0], &[vec![alpha]], phi).unwrap();
    let hcs = theory.hcs_sonine(target).unwrap();
    let text = monodisperse(
        phi,
        n,
        alpha,
        "kind = \"gaussian-thermostat\"",
        "engine = \"event-driven\"\ncollisions_per_particle = 200\nsamples = 401",
    );
    let (_, a2, _, s) = steady(&text, 10.0);
    let zeta_dt = hcs.cooling_rate * s.plan().driving_interval.unwrap();
    for x in s.samples() {
        let t = x.temperature / target;
        assert!(
            t <= 1.0 + 1e-9 && t >= 1.0 - 2.0 * zeta_dt,
            "T {t} at {}",
            x.time
        );
    }
    eprintln!("thermostat, event-driven: a2 {a2:.5} vs {:.5}", hcs.a2[0]);
    assert!(
        (a2 / hcs.a2[0] - 1.0).abs() < 0.4,
        "a2 {a2} vs {}",
        hcs.a2[0]
    );
}

/// The thermostat on a binary mixture (3D, m1/m0 = 4, alpha = 0.8, phi = 0.1, DSMC, N =
/// 5e4): the steady temperature ratio is the HCS's, and the run decides between the two
/// approximations (which differ by 0.7 %, ten standard errors of the measured mean): it
/// lies nearer the first Sonine ratio than the Maxwellian one.
#[test]
fn a_thermostatted_mixture_has_the_hcs_temperature_ratio() {
    let (alpha, phi) = (0.8, 0.1);
    let text = format!(
        "[system]\ndimension = 3\nparticles = 50000\npacking_fraction = {phi}\nseed = 5\n\
         species = [{{ diameter = 1.0, mass = 1.0, fraction = 0.5 }}, \
         {{ diameter = 1.0, mass = 4.0, fraction = 0.5 }}]\n\
         [collision]\nlaw = \"constant\"\nrestitution = {alpha}\n\
         [driving]\nkind = \"gaussian-thermostat\"\n\
         [run]\nengine = \"dsmc\"\ncollisions_per_particle = 60\nsamples = 121\nspacing = \"linear\"\n"
    );
    let d = RunDescription::from_toml(&text, Path::new("m.toml")).unwrap();
    let mut s = Simulation::new(&d).unwrap();
    s.run(&mut (), None).unwrap();
    let ratios: Vec<f64> = s
        .species_samples()
        .unwrap()
        .chunks(2)
        .filter(|p| p[0].collisions_per_particle >= 15.0)
        .map(|p| p[1].temperature / p[0].temperature)
        .collect();
    let n = ratios.len() as f64;
    let mean = ratios.iter().sum::<f64>() / n;
    let theory = MixtureTheory::<3>::new(
        &[1.0, 4.0],
        &[1.0, 1.0],
        &[0.5, 0.5],
        &[vec![alpha; 2], vec![alpha; 2]],
        phi,
    )
    .unwrap();
    let ratio = |r: &[f64]| r[1] / r[0];
    let maxwell = ratio(&theory.hcs(1.0).unwrap().temperature_ratios);
    let sonine = ratio(&theory.hcs_sonine(1.0).unwrap().temperature_ratios);
    eprintln!("thermostat, mixture: T1/T0 {mean:.4}; Sonine {sonine:.4}, Maxwellian {maxwell:.4}");
    assert!((mean - sonine).abs() < (mean - maxwell).abs(), "{mean}");
    assert!((mean / sonine - 1.0).abs() < 0.005, "{mean} vs {sonine}");
}

/// White noise across restitutions (3D, phi = 0.1, DSMC blocks, N = 1e5): the steady a2
/// against van Noije & Ernst's first Sonine value (`gas::theory::MixtureTheory::
/// white_noise`; positive below alpha = 1/sqrt(2), negative above), and the temperature
/// against the energy balance. Prints the table of docs/mixtures.md; asserts a2 within 3
/// standard errors (ten block means) plus 10 % of the Sonine value (the neglected a3) and
/// T within 1 %.
#[test]
#[ignore = "heavy: ~15 s; cargo test --release -p haff-sim --test driving -- --ignored --nocapture"]
fn white_noise_a2_follows_van_noije_ernst() {
    let (n, phi) = (100_000usize, 0.1);
    eprintln!("alpha  T_DSMC  T_Sonine  a2_DSMC  a2_Sonine");
    // (alpha, first sample averaged, end), in collisions per particle: the approach to the
    // steady state slows as alpha -> 1 (the energy relaxes at 3 zeta / 2).
    for (alpha, from, end) in [
        (0.3, 20.0, 80.0),
        (0.5, 20.0, 80.0),
        (0.8, 30.0, 100.0),
        (0.9, 80.0, 200.0),
    ] {
        let theory = MixtureTheory::<3>::new(&[1.0], &[1.0], &[1.0], &[vec![alpha]], phi).unwrap();
        let block = gas::dsmc::DEFAULT_BLOCK_SIZE as f64;
        let want = theory.white_noise(&[1.0 - 1.0 / block], true).unwrap();
        let text = monodisperse(
            phi,
            n,
            alpha,
            "kind = \"white-noise\"\nstrength = 1.0",
            &format!("engine = \"dsmc\"\ncollisions_per_particle = {end}\nsamples = 201"),
        );
        let (t, a2, (t_error, a2_error), _) = steady_with_errors(&text, from);
        let sonine = want.a2[0];
        eprintln!(
            "{alpha}  {t:.4} +- {t_error:.4}  {:.4}  {a2:.4} +- {a2_error:.4}  {sonine:.4}",
            want.temperatures[0]
        );
        assert!(
            (a2 - sonine).abs() < 3.0 * a2_error + 0.1 * sonine.abs(),
            "a2 {a2}"
        );
        assert!((t / want.temperatures[0] - 1.0).abs() < 0.01, "T {t}");
    }
}

/// White noise in the event-driven engine at densities 0.01 to 0.2 (3D, alpha = 0.8,
/// N = 4000): the steady temperature against the Enskog–Sonine balance, which assumes
/// molecular chaos. Dilute, they agree (within 3 standard errors at phi = 0.01); denser, the
/// event-driven gas is hotter, by more the denser it is: the noise builds velocity
/// correlations that lower the collision frequency below Enskog's (van Noije, Ernst,
/// Trizac & Pagonabarraga, Phys. Rev. E 59, 4326 (1999)); DSMC, molecular chaos by
/// construction, follows the balance (`white_noise_a2_follows_van_noije_ernst`).
#[test]
#[ignore = "heavy: ~15 s; cargo test --release -p haff-sim --test driving -- --ignored --nocapture"]
fn event_driven_white_noise_departs_from_enskog_with_density() {
    let (n, alpha) = (4000usize, 0.8);
    let mut excess = Vec::new();
    for phi in [0.01, 0.05, 0.1, 0.2] {
        let theory = MixtureTheory::<3>::new(&[1.0], &[1.0], &[1.0], &[vec![alpha]], phi).unwrap();
        let want = theory
            .white_noise(&[1.0 - 1.0 / n as f64], true)
            .unwrap()
            .temperatures[0];
        let text = monodisperse(
            phi,
            n,
            alpha,
            "kind = \"white-noise\"\nstrength = 1.0",
            "engine = \"event-driven\"\ncollisions_per_particle = 200\nsamples = 401",
        );
        let (t, _, error, _) = steady(&text, 20.0);
        eprintln!(
            "phi {phi}: T {t:.4} +- {error:.4} vs Enskog-Sonine {want:.4} ({:+.4})",
            t / want - 1.0
        );
        excess.push((t / want - 1.0, error / want));
    }
    assert!(excess[0].0.abs() < 3.0 * excess[0].1, "{excess:?}");
    for pair in excess.windows(2) {
        assert!(pair[1].0 > pair[0].0, "{excess:?}");
    }
    assert!(excess[3].0 > 10.0 * excess[3].1, "{excess:?}");
}

/// The high-energy tail of the white-noise state (3D, alpha = 0.5, phi = 0.05, DSMC,
/// N = 2e5, 60 snapshots of the steady state): the speed distribution f(c) for c in
/// [2.5, 4.5] (c = v / sqrt(2T/m)) is fitted by ln f = a + g ln c - A' c^(3/2) (weighted
/// least squares, weights the bin counts: the variance of ln of a Poisson count n is
/// 1/n), the power-law prefactor c^g free as the WKB balance leaves it; the fitted
/// exponent A' is van Noije & Ernst's A = (2/3) sqrt(2 beta / xi^2) (in scaled speeds,
/// beta = chi n sigma^2 pi) within 3 of the fit's standard errors plus 10 % (the next
/// order of the asymptotic expansion, not computed here). Measured: A' = 2.199 +- 0.069
/// against A = 2.109, prefactor power 1.5.
#[test]
fn the_white_noise_tail_decays_as_exp_of_c_to_the_three_halves() {
    use std::f64::consts::PI;
    let (n, phi, alpha, xi2) = (200_000usize, 0.05, 0.5, 1.0);
    let text = monodisperse(
        phi,
        n,
        alpha,
        &format!("kind = \"white-noise\"\nstrength = {xi2}"),
        "engine = \"dsmc\"\ncollisions_per_particle = 200\ncollisions_per_step = 0.5\nsamples = 2",
    );
    let d = RunDescription::from_toml(&text, Path::new("tail.toml")).unwrap();
    let mut s = Simulation::new(&d).unwrap();
    let (bins, c_max) = (80usize, 5.0);
    let mut counts = vec![0.0; bins];
    let (mut total, mut temperature) = (0.0, 0.0);
    for k in 0..60 {
        s.advance(
            sim::Point::CollisionsPerParticle(40.0 + 2.0 * k as f64),
            &mut (),
        )
        .unwrap();
        let t = s.temperature();
        temperature += t / 60.0;
        let v_th = (2.0 * t).sqrt();
        for v in s.particles().velocities.chunks_exact(3) {
            let c = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() / v_th;
            let b = (c / c_max * bins as f64) as usize;
            if b < bins {
                counts[b] += 1.0;
            }
            total += 1.0;
        }
    }
    let width = c_max / bins as f64;
    // Rows (1, ln c, -c^(3/2)) against ln f, weight n.
    let rows: Vec<([f64; 3], f64, f64)> = counts
        .iter()
        .enumerate()
        .map(|(b, &count)| ((b as f64 + 0.5) * width, count))
        .filter(|&(c, count)| (2.5..=4.5).contains(&c) && count >= 5.0)
        .map(|(c, count)| {
            let f = count / (total * 4.0 * PI * c * c * width);
            ([1.0, c.ln(), -c.powf(1.5)], f.ln(), count)
        })
        .collect();
    let mut normal = [[0.0; 3]; 3];
    let mut rhs = [0.0; 3];
    for (x, y, w) in &rows {
        for i in 0..3 {
            rhs[i] += w * x[i] * y;
            for j in 0..3 {
                normal[i][j] += w * x[i] * x[j];
            }
        }
    }
    let inverse = invert(normal);
    let fit: Vec<f64> = (0..3)
        .map(|i| (0..3).map(|j| inverse[i][j] * rhs[j]).sum())
        .collect();
    let error = inverse[2][2].sqrt();
    let density = phi / (PI / 6.0);
    let beta = gas::theory::contact_value::<3>(phi) * density * PI;
    let want = (2.0 / 3.0) * (2.0 * beta / xi2).sqrt() * (2.0 * temperature).powf(0.75);
    eprintln!(
        "tail: A' = {:.4} +- {error:.4} (prefactor power {:.2}; {} bins) vs A = {want:.4}",
        fit[2],
        fit[1],
        rows.len()
    );
    assert!((fit[2] - want).abs() < 3.0 * error + 0.1 * want);
}

/// The inverse of a 3 x 3 matrix (cofactors).
fn invert(m: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
            let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
            (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det
        })
    })
}
