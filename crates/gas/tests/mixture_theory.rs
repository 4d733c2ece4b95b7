//! The kinetic theory of a mixture's HCS (`gas::theory::mixture`) against independent
//! computations: the one-species theory of `gas::theory`, a Monte Carlo integral of the
//! collision operator over Maxwellians at unequal temperatures, and the elastic limit.

use gas::theory::{self, MixtureTheory};
use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64;

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
    fn check<const D: usize>(seed: u64) {
        let masses = [1.0, 3.5];
        let diameters = [1.0, 1.8];
        let alpha = [[0.9, 0.6], [0.6, 0.75]];
        let temperatures = [1.0, 2.3];
        let mixture = binary::<D>(masses, diameters, 0.4, alpha, 0.15);
        let nu = |i, j| mixture.pair_frequency(i, j, &temperatures);
        let zeta = mixture.cooling_rates(&temperatures);
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
                        let kick = mu * (1.0 + alpha[i][j]) * approach;
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
    check::<1>(1);
    check::<2>(2);
    check::<3>(3);
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
