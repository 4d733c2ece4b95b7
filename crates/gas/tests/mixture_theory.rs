//! The kinetic theory of a mixture's HCS (`gas::theory::mixture`) against independent
//! computations: the one-species theory of `gas::theory`, a Monte Carlo integral of the
//! collision operator over Maxwellians at unequal temperatures (constant and viscoelastic
//! restitution), closed forms of free cooling, and the elastic limit.

use gas::theory::{self, MixtureTheory};
use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64;
use restitution::{Restitution, Viscoelastic};

fn binary<const D: usize>(
    masses: [f64; 2],
    diameters: [f64; 2],
    x1: f64,
    alpha: [[f64; 2]; 2],
    phi: f64,
) -> MixtureTheory<D> {
    let restitution: Vec<Vec<f64>> = alpha.iter().map(|r| r.to_vec()).collect();
    MixtureTheory::<D>::new(&masses, &diameters, &[x1, 1.0 - x1], &restitution, phi).unwrap()
}

/// One species, and two identical species: the collision frequency of
/// `theory::collision_frequency`, zeta = (1 - alpha^2) omega / D, ratios 1. (Up to rounding:
/// the same formula reached two ways.)
#[test]
fn one_species_is_the_pure_theory() {
    fn check<const D: usize>() {
        let (m, sigma, alpha, phi, t) = (2.0, 1.3, 0.8, 0.1, 1.7);
        let pure = MixtureTheory::<D>::new(&[m], &[sigma], &[1.0], &[vec![alpha]], phi).unwrap();
        let n = pure.density();
        let omega = theory::collision_frequency::<D>(n, sigma, m, t, phi);
        let hcs = pure.hcs(t).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert!(close(hcs.collision_frequencies[0], omega), "{D}D");
        assert!(close(
            hcs.cooling_rate,
            (1.0 - alpha * alpha) * omega / D as f64
        ));
        let twins = binary::<D>([m, m], [sigma, sigma], 0.3, [[alpha; 2]; 2], phi);
        let hcs = twins.hcs(t).unwrap();
        for i in 0..2 {
            assert!(close(hcs.temperature_ratios[i], 1.0));
            assert!(close(hcs.collision_frequencies[i], omega), "{D}D twins");
        }
        assert!(close(
            hcs.cooling_rate,
            (1.0 - alpha * alpha) * omega / D as f64
        ));
    }
    check::<1>();
    check::<2>();
    check::<3>();
}

/// nu_ij and zeta_i from a Monte Carlo integral of the collision operator: velocities
/// drawn from Maxwellians at T_1 != T_2, impact directions uniform on the sphere, the energy
/// change of particle 1 computed from the collision rule itself. 4e5 samples per pair;
/// agreement within 5 standard errors of the sample mean.
#[test]
fn rates_match_a_monte_carlo_integral_of_the_collision_operator() {
    fn check<const D: usize>(seed: u64, viscoelastic: bool) {
        let masses = [1.0, 3.5];
        let diameters = [1.0, 1.8];
        let alpha = [[0.9, 0.6], [0.6, 0.75]];
        let temperatures = [1.0, 2.3];
        let mixture = binary::<D>(masses, diameters, 0.4, alpha, 0.15);
        let nu = |i, j| mixture.pair_frequency(i, j, &temperatures);
        // Velocity-dependent: viscoelastic laws of beta 0.1, 0.4 (unlike), 0.2.
        let laws: Vec<Viscoelastic> = [0.1, 0.4, 0.2]
            .map(|beta| Viscoelastic::new(beta, "fast".parse().unwrap()).unwrap())
            .into();
        let eps = |i: usize, j: usize, g: f64| {
            if viscoelastic {
                laws[i + j].eps(g)
            } else {
                alpha[i][j]
            }
        };
        let zeta = if viscoelastic {
            mixture.cooling_rates_for(&temperatures, &eps)
        } else {
            mixture.cooling_rates(&temperatures)
        };
        let mut rng = Pcg64::seed_from_u64(seed);
        let samples = 400_000;
        let surface = theory::sphere_surface::<D>();
        for i in 0..2 {
            let mut zeta_mc = 0.0;
            let mut zeta_var = 0.0;
            for j in 0..2 {
                let sigma = 0.5 * (diameters[i] + diameters[j]);
                let fraction = if j == 0 { 0.4 } else { 0.6 };
                let prefactor = mixture.contact_value(i, j)
                    * fraction
                    * mixture.density()
                    * sigma.powi(D as i32 - 1)
                    * surface;
                let mu = masses[j] / (masses[i] + masses[j]);
                let (mut f, mut f2, mut e, mut e2) = (0.0, 0.0, 0.0, 0.0);
                for _ in 0..samples {
                    let gauss = |rng: &mut Pcg64, var: f64| -> [f64; D] {
                        std::array::from_fn(|_| {
                            var.sqrt()
                                * <StandardNormal as Distribution<f64>>::sample(
                                    &StandardNormal,
                                    rng,
                                )
                        })
                    };
                    let v1 = gauss(&mut rng, temperatures[i] / masses[i]);
                    let v2 = gauss(&mut rng, temperatures[j] / masses[j]);
                    let direction = unit::<D>(&mut rng);
                    let g: [f64; D] = std::array::from_fn(|k| v1[k] - v2[k]);
                    let approach: f64 = (0..D).map(|k| g[k] * direction[k]).sum();
                    let (rate, de) = if approach > 0.0 {
                        let kick = mu * (1.0 + eps(i, j, approach)) * approach;
                        let after: f64 =
                            (0..D).map(|k| (v1[k] - kick * direction[k]).powi(2)).sum();
                        let before: f64 = v1.iter().map(|v| v * v).sum();
                        (approach, approach * 0.5 * masses[i] * (after - before))
                    } else {
                        (0.0, 0.0)
                    };
                    f += rate;
                    f2 += rate * rate;
                    e += de;
                    e2 += de * de;
                }
                let n = samples as f64;
                let (mean_f, var_f) = (f / n, (f2 / n - (f / n).powi(2)) / n);
                let nu_mc = prefactor * mean_f;
                let error = prefactor * var_f.sqrt();
                assert!(
                    (nu_mc - nu(i, j)).abs() < 5.0 * error,
                    "{D}D nu_{i}{j}: MC {nu_mc} +- {error}, theory {}",
                    nu(i, j)
                );
                // dT_i/dt = (2 / D) <dE_i rate>, zeta_i = -(dT_i/dt) / T_i.
                let scale = -2.0 / (D as f64 * temperatures[i]) * prefactor;
                zeta_mc += scale * e / n;
                zeta_var += scale * scale * (e2 / n - (e / n).powi(2)) / n;
            }
            let error = zeta_var.sqrt();
            assert!(
                (zeta_mc - zeta[i]).abs() < 5.0 * error,
                "{D}D zeta_{i}: MC {zeta_mc} +- {error}, theory {}",
                zeta[i]
            );
        }
    }
    for viscoelastic in [false, true] {
        check::<1>(1, viscoelastic);
        check::<2>(2, viscoelastic);
        check::<3>(3, viscoelastic);
    }
}

/// A uniformly random unit vector in D dimensions.
fn unit<const D: usize>(rng: &mut Pcg64) -> [f64; D] {
    if D == 1 {
        return std::array::from_fn(|_| if rng.random::<bool>() { 1.0 } else { -1.0 });
    }
    let v: [f64; D] = std::array::from_fn(|_| {
        <StandardNormal as Distribution<f64>>::sample(&StandardNormal, rng)
    });
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.map(|x| x / norm)
}

/// Elastic collisions keep equipartition (T_i = T for any masses and sizes, zeta = 0); with
/// equal restitution the heavier species is the hotter one (as Garzó & Dufty 1999 find);
/// the HCS equalizes the cooling rates, sum x_i T_i / T = 1, and relabelling the species
/// permutes the ratios.
#[test]
fn hcs_properties() {
    let elastic = binary::<3>([1.0, 4.0], [1.0, 2.0], 0.3, [[1.0; 2]; 2], 0.2);
    let hcs = elastic.hcs(1.0).unwrap();
    for r in &hcs.temperature_ratios {
        assert!((r - 1.0).abs() < 1e-12, "{r}");
    }
    assert!(hcs.cooling_rate.abs() < 1e-12);
    for d in [1, 2, 3] {
        let ratios = |m: [f64; 2], s: [f64; 2], x: f64| -> Vec<f64> {
            let alpha = [[0.8; 2]; 2];
            let r = match d {
                1 => binary::<1>(m, s, x, alpha, 0.1).hcs(1.0),
                2 => binary::<2>(m, s, x, alpha, 0.1).hcs(1.0),
                _ => binary::<3>(m, s, x, alpha, 0.1).hcs(1.0),
            };
            r.unwrap().temperature_ratios
        };
        let r = ratios([1.0, 5.0], [1.0, 1.2], 0.6);
        assert!(r[1] > r[0], "{d}D: heavy {} light {}", r[1], r[0]);
        assert!((0.6 * r[0] + 0.4 * r[1] - 1.0).abs() < 1e-12);
        let swapped = ratios([5.0, 1.0], [1.2, 1.0], 0.4);
        assert!((swapped[0] - r[1]).abs() < 1e-9 && (swapped[1] - r[0]).abs() < 1e-9);
    }
    let three = MixtureTheory::<3>::new(
        &[1.0, 2.0, 6.0],
        &[1.0, 1.3, 2.0],
        &[0.5, 0.3, 0.2],
        &[
            vec![0.9, 0.8, 0.7],
            vec![0.8, 0.85, 0.6],
            vec![0.7, 0.6, 0.5],
        ],
        0.25,
    )
    .unwrap();
    let hcs = three.hcs(2.0).unwrap();
    let at: Vec<f64> = hcs.temperature_ratios.iter().map(|r| 2.0 * r).collect();
    let zeta = three.cooling_rates(&at);
    for z in &zeta {
        assert!((z / zeta[0] - 1.0).abs() < 1e-10, "{zeta:?}");
    }
    assert!((hcs.cooling_rate - zeta[0]).abs() < 1e-12 * zeta[0]);
}

/// Bad input names the parameter.
#[test]
fn bad_input_is_named() {
    let e = |r: gas::Result<MixtureTheory<3>>| r.unwrap_err().to_string();
    let alpha = vec![vec![0.9, 0.8], vec![0.7, 0.9]];
    assert!(e(MixtureTheory::new(
        &[1.0, 1.0],
        &[1.0, 1.0],
        &[0.5, 0.5],
        &alpha,
        0.1
    ))
    .contains("restitution"));
    let alpha = vec![vec![0.9; 2]; 2];
    assert!(e(MixtureTheory::new(
        &[1.0, -1.0],
        &[1.0, 1.0],
        &[0.5, 0.5],
        &alpha,
        0.1
    ))
    .contains("masses"));
    assert!(e(MixtureTheory::new(
        &[1.0, 1.0],
        &[1.0, 1.0],
        &[0.5, 0.6],
        &alpha,
        0.1
    ))
    .contains("fractions"));
    assert!(e(MixtureTheory::new(
        &[1.0, 1.0],
        &[1.0, 1.0],
        &[0.5, 0.5],
        &alpha,
        0.9
    ))
    .contains("packing_fraction"));
}

/// One species (and identical twins) in the first Sonine approximation: a2 of van Noije &
/// Ernst (`theory::van_noije_ernst_a2`, the same linearization, closed form) to 1e-10, the
/// cooling rate (1 + 3 a2/16) and the collision frequency (1 - a2/16) times the
/// Maxwellian ones (van Noije & Ernst 1998; Brilliantov & Pöschel 2004, Ch. 7): checks of
/// the quadrature of the collision integrals. Elastic mixtures stay Maxwellian.
#[test]
fn sonine_one_species_is_van_noije_ernst() {
    fn check<const D: usize>(alpha: f64) {
        let want = theory::van_noije_ernst_a2::<D>(alpha);
        let pure = MixtureTheory::<D>::new(&[1.5], &[1.0], &[1.0], &[vec![alpha]], 0.1).unwrap();
        let (sonine, maxwell) = (pure.hcs_sonine(2.0).unwrap(), pure.hcs(2.0).unwrap());
        let a2 = sonine.a2[0];
        assert!(
            (a2 - want).abs() < 1e-10,
            "{D}D alpha {alpha}: a2 {a2} vs {want}"
        );
        let zeta = maxwell.cooling_rate * (1.0 + 3.0 * a2 / 16.0);
        assert!(
            (sonine.cooling_rate / zeta - 1.0).abs() < 1e-10,
            "{D}D zeta"
        );
        let nu = maxwell.collision_frequencies[0] * (1.0 - a2 / 16.0);
        assert!(
            (sonine.collision_frequencies[0] / nu - 1.0).abs() < 1e-10,
            "{D}D nu"
        );
        let twins = binary::<D>([1.5, 1.5], [1.0, 1.0], 0.3, [[alpha; 2]; 2], 0.1);
        let hcs = twins.hcs_sonine(2.0).unwrap();
        for i in 0..2 {
            assert!((hcs.temperature_ratios[i] - 1.0).abs() < 1e-10);
            assert!(
                (hcs.a2[i] - want).abs() < 1e-10,
                "{D}D twins a2 {}",
                hcs.a2[i]
            );
        }
    }
    for alpha in [0.3, 0.7, 0.9] {
        check::<2>(alpha);
        check::<3>(alpha);
    }
    let elastic = binary::<3>([1.0, 4.0], [1.0, 2.0], 0.3, [[1.0; 2]; 2], 0.2);
    let hcs = elastic.hcs_sonine(1.0).unwrap();
    for i in 0..2 {
        assert!((hcs.temperature_ratios[i] - 1.0).abs() < 1e-10 && hcs.a2[i].abs() < 1e-10);
    }
}

/// White-noise driving, one species: the steady a2 of van Noije & Ernst (1998; Montanero &
/// Santos, Granular Matter 2, 53 (2000)),
/// a2 = 16 (1 - a)(1 - 2a^2) / (73 + 56 D - 3a (35 + 8D) + 30 (1 - a) a^2), to 1e-10: the
/// formula is the authors' closed form, our number the quadrature of the collision
/// integrals; and the energy balance zeta(T) T = m xi^2 with
/// zeta = (1 + 3 a2/16) zeta_Maxwell(T).
#[test]
fn white_noise_one_species_is_van_noije_ernst() {
    fn check<const D: usize>(alpha: f64) {
        let d = D as f64;
        let want = 16.0 * (1.0 - alpha) * (1.0 - 2.0 * alpha * alpha)
            / (73.0 + 56.0 * d - 3.0 * alpha * (35.0 + 8.0 * d)
                + 30.0 * (1.0 - alpha) * alpha * alpha);
        let (m, xi2) = (1.5, 0.7);
        let pure = MixtureTheory::<D>::new(&[m], &[1.0], &[1.0], &[vec![alpha]], 0.1).unwrap();
        let steady = pure.white_noise(&[xi2], true).unwrap();
        let a2 = steady.a2[0];
        assert!(
            (a2 - want).abs() < 1e-10,
            "{D}D alpha {alpha}: a2 {a2} vs {want}"
        );
        let t = steady.temperatures[0];
        let zeta = pure.cooling_rates(&[t])[0] * (1.0 + 3.0 * a2 / 16.0);
        assert!((zeta * t / (m * xi2) - 1.0).abs() < 1e-10, "{D}D balance");
        let maxwell = pure.white_noise(&[xi2], false).unwrap();
        let zeta = pure.cooling_rates(&maxwell.temperatures)[0];
        assert!((zeta * maxwell.temperatures[0] / (m * xi2) - 1.0).abs() < 1e-10);
    }
    for alpha in [0.3, 0.7, 0.9] {
        check::<2>(alpha);
        check::<3>(alpha);
    }
}

/// Speed-dependent restitution: a constant eps gives the constant-alpha rates; eps =
/// 1 - c g (one species) gives zeta = (omega / D) <1 - eps^2>_3 with the moments
/// <u>_3 = (3/2) sqrt(pi/2) and <u^2>_3 = 4 of the weight u^3 exp(-u^2/2) (closed forms).
#[test]
fn speed_dependent_rates_reduce_to_closed_forms() {
    let mixture = binary::<3>([1.0, 3.5], [1.0, 1.8], 0.4, [[0.9, 0.6], [0.6, 0.75]], 0.15);
    let t = [1.0, 2.3];
    let alpha = [[0.9, 0.6], [0.6, 0.75]];
    let constant = mixture.cooling_rates_for(&t, &|i, j, _| alpha[i][j]);
    for (a, b) in constant.iter().zip(mixture.cooling_rates(&t)) {
        assert!((a / b - 1.0).abs() < 1e-12, "{a} vs {b}");
    }
    let (m, sigma, phi, temperature, c) = (2.0, 1.3, 0.1, 1.7, 0.05);
    let pure = MixtureTheory::<2>::new(&[m], &[sigma], &[1.0], &[vec![1.0]], phi).unwrap();
    let omega = pure.collision_frequencies(&[temperature])[0];
    // Relative velocity per component: s^2 = 2 T / m.
    let s = (2.0 * temperature / m).sqrt();
    let loss = 2.0 * c * s * 1.5 * (std::f64::consts::PI / 2.0).sqrt() - c * c * s * s * 4.0;
    let zeta = pure.cooling_rates_for(&[temperature], &|_, _, g| 1.0 - c * g)[0];
    assert!((zeta / (omega * loss / 2.0) - 1.0).abs() < 1e-9, "{zeta}");
}

/// Free cooling against closed forms. Constant alpha: Haff, T = T0 / (1 + zeta0 t / 2)^2.
/// 1 - eps^2 = c g^(1/5) exactly: zeta ~ T^(3/5), so T = T0 (1 + (3/5) zeta0 t)^(-5/3),
/// the late-time law of viscoelastic spheres; zeta0 = (omega / D) c s^(1/5) <u^(1/5)>_3
/// with <u^(1/5)>_3 = 2^(1/10) Gamma(2.1) (Gamma(2.1) = 1.0464858468535, Python's
/// math.gamma). Runge–Kutta with 50 steps per unit of ln(1 + nu0 t): 1e-8.
#[test]
fn free_cooling_follows_haff_and_the_viscoelastic_power_law() {
    let (m, sigma, phi, t0) = (1.0, 1.0, 0.1, 1.0);
    let times = [0.0, 1.0, 10.0, 100.0, 1e4];
    let alpha = 0.8;
    let haff = MixtureTheory::<3>::new(&[m], &[sigma], &[1.0], &[vec![alpha]], phi).unwrap();
    let zeta0 = haff.cooling_rates(&[t0])[0];
    let cooled = haff
        .free_cooling(&[t0], &|_, _, _| alpha, &times, 50)
        .unwrap();
    for (t, row) in times.iter().zip(&cooled) {
        let want = t0 / (1.0 + zeta0 * t / 2.0).powi(2);
        assert!(
            (row[0] / want - 1.0).abs() < 1e-8,
            "t = {t}: {} vs {want}",
            row[0]
        );
    }
    let c = 0.2;
    let eps = |_: usize, _: usize, g: f64| (1.0 - c * g.powf(0.2)).max(0.0).sqrt();
    let omega = haff.collision_frequencies(&[t0])[0];
    let s = (2.0 * t0 / m).sqrt();
    let zeta0 = omega / 3.0 * c * s.powf(0.2) * 2f64.powf(0.1) * 1.046_485_846_853_5;
    assert!((haff.cooling_rates_for(&[t0], &eps)[0] / zeta0 - 1.0).abs() < 1e-9);
    let cooled = haff.free_cooling(&[t0], &eps, &times, 50).unwrap();
    for (t, row) in times.iter().zip(&cooled) {
        let want = t0 * (1.0 + 0.6 * zeta0 * t).powf(-5.0 / 3.0);
        assert!(
            (row[0] / want - 1.0).abs() < 1e-8,
            "t = {t}: {} vs {want}",
            row[0]
        );
    }
    assert!(haff.free_cooling(&[t0], &eps, &[2.0, 1.0], 50).is_err());
    assert!(haff.free_cooling(&[-1.0], &eps, &[1.0], 50).is_err());
}
