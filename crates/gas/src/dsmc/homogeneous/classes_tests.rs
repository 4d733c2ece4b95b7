//! Tests of the speed-class process of `classes.rs`.
use super::*;
use crate::dsmc::species::Species;
use crate::engine::Counters;
use crate::rng::Purpose;
use restitution::Constant;

fn maxwellian(n: usize, seed: u64) -> Vec<Vector<3>> {
    let s = crate::dsmc::point_gas::<3>(n, 1.0, 1.0, 1.0, 1.0, seed).unwrap();
    s.velocities
}

/// Every record lies in its class's range, its class is the class of its speed, and
/// the class bound holds: |v - reference| <= m w; M_tot is the sum of the multipliers.
fn check_classes<const D: usize>(
    group: &[Vector<D>],
    class: &[u8],
    classes: &Classes,
    reference: &Vector<D>,
) {
    let mut total = 0;
    for a in 0..CLASSES {
        for p in classes.start[a]..classes.start[a + 1] {
            let s2 = speed2(&group[p], reference);
            assert_eq!(class[p] as usize, a, "record {p}");
            assert_eq!(classes.class_of(s2), a, "record {p}");
            assert!(
                s2.sqrt() <= classes.class_bound(a),
                "record {p} in class {a}"
            );
            assert!(s2.sqrt() <= classes.bound);
            total += classes.multiplier(a);
        }
    }
    assert_eq!(classes.start[CLASSES], group.len());
    assert_eq!(total, classes.total);
}

/// The class majorants bound every speed after every collision (and so after every
/// step), with a hot particle beyond the classes (the top class and its raised bound),
/// through cooling (eps = 0.5) and elastic runs; sorting a sorted group changes
/// nothing.
#[test]
fn class_bounds_hold_after_every_collision() {
    for eps in [0.5, 1.0] {
        let mut group = maxwellian(600, 3);
        group[17] = [9.0, -2.0, 1.0];
        let reference = [0.0; 3];
        let law = Constant::new(eps).unwrap();
        let (species, _) = Species::of::<3>(&[0.5; 600], &[1.0; 600], 0.1).unwrap();
        let collider = Collider {
            rough: None,
            law: &law,
            species: &species,
            pairs: None,
        };
        let mut rng = Stream::new(5, Purpose::Block, 0, 0);
        let mut tally = Counters::default();
        let mut class = Vec::new();
        let bound = crate::dsmc::kernel::speed_bound(&group, &reference);
        let width = class_width(1.0, 1.0, bound);
        let mut classes = Classes::sort(&mut group, &mut class, &reference, width, bound);
        check_classes(&group, &class, &classes, &reference);
        let mut time = 0.0;
        for _ in 0..3000 {
            let window = Window {
                start: time,
                end: f64::INFINITY,
                max_collisions: 1,
            };
            time = collider.run_classes(
                &mut group,
                &mut class,
                &mut classes,
                &reference,
                1e-3,
                window,
                &mut rng,
                &mut tally,
            );
            check_classes(&group, &class, &classes, &reference);
        }
        assert_eq!(tally.collisions, 3000);
        let before = group.clone();
        let again = Classes::sort(&mut group, &mut class, &reference, width, classes.bound);
        assert_eq!(group, before);
        assert_eq!(again.start, classes.start);
        assert_eq!(again.total, classes.total);
    }
}

/// The process over 8 particles of known velocities (one fast, in the top class)
/// against the exact enumeration of the master equation, 2e5 first collisions each
/// from the same state (copies of the records and classes): the colliding pair has
/// probability |g_ij| / sum |g| (chi-square over the 28 pairs, 27 degrees of freedom,
/// bound 65: P(chi2 > 65) = 6e-5); the waiting time is exponential of rate
/// P sum |g| (its mean within 5 standard errors, mean / sqrt(count)); candidates per
/// collision are geometric with mean (n - 1) w M_tot / sum |g| (within 5 standard
/// errors, sqrt(1 - p) / p / sqrt(count)). The candidate draw alone against its
/// probability (m_i + m_j) / ((n - 1) M_tot): chi-square over 1e6 draws, same bound.
#[test]
fn colliding_pairs_follow_the_master_equation() {
    let mut group: Vec<Vector<3>> = maxwellian(8, 11);
    group[2] = [7.0, 3.0, 0.0];
    let reference = [0.0; 3];
    let bound = crate::dsmc::kernel::speed_bound(&group, &reference);
    let mut class = Vec::new();
    let width = class_width(1.0, 1.0, bound);
    let classes = Classes::sort(&mut group, &mut class, &reference, width, bound);
    assert!(class.contains(&(CLASSES as u8 - 1)));
    let n = group.len();
    let m: Vec<u64> = class
        .iter()
        .map(|&a| classes.multiplier(a as usize))
        .collect();
    let speed = |i: usize, j: usize| -> f64 {
        let g: Vector<3> = std::array::from_fn(|k| group[i][k] - group[j][k]);
        dot(&g, &g).sqrt()
    };
    let pairs: Vec<(usize, usize)> = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect();
    let total_g: f64 = pairs.iter().map(|&(i, j)| speed(i, j)).sum();
    let chi2 = |counts: &[u64], probability: &dyn Fn(usize, usize) -> f64| {
        let total: u64 = counts.iter().sum();
        pairs
            .iter()
            .zip(counts)
            .map(|(&(i, j), &c)| {
                let expected = total as f64 * probability(i, j);
                (c as f64 - expected).powi(2) / expected
            })
            .sum::<f64>()
    };
    let law = Constant::new(1.0).unwrap();
    let (species, _) = Species::of::<3>(&[0.5; 8], &[1.0; 8], 0.1).unwrap();
    let collider = Collider {
        rough: None,
        law: &law,
        species: &species,
        pairs: None,
    };
    let pair_rate = 0.01;
    let mut rng = Stream::new(8, Purpose::Block, 1, 2);
    let mut tally = Counters::default();
    let mut hits = vec![0u64; pairs.len()];
    let mut time = 0.0;
    let runs = 200_000;
    for _ in 0..runs {
        let (mut g, mut c, mut k) = (group.clone(), class.clone(), classes.clone());
        let window = Window {
            start: 0.0,
            end: f64::INFINITY,
            max_collisions: 1,
        };
        time += collider.run_classes(
            &mut g, &mut c, &mut k, &reference, pair_rate, window, &mut rng, &mut tally,
        );
        // The pair is the two records no longer present.
        let gone: Vec<usize> = (0..n).filter(|&i| !g.contains(&group[i])).collect();
        assert_eq!(gone.len(), 2);
        hits[pairs.iter().position(|&p| p == (gone[0], gone[1])).unwrap()] += 1;
    }
    let chi_collisions = chi2(&hits, &|i, j| speed(i, j) / total_g);
    let mean_time = time / runs as f64;
    let expected_time = 1.0 / (pair_rate * total_g);
    let time_error = expected_time / (runs as f64).sqrt();
    let p = total_g / ((n - 1) as f64 * width * classes.total as f64);
    let per_collision = tally.events as f64 / runs as f64;
    let per_collision_error = (1.0 - p).sqrt() / p / (runs as f64).sqrt();
    let mut candidates = vec![0u64; pairs.len()];
    for _ in 0..1_000_000 {
        let (i, j) = classes.pick(n, &mut rng);
        let (i, j) = (i.min(j), i.max(j));
        candidates[pairs.iter().position(|&p| p == (i, j)).unwrap()] += 1;
    }
    let total_m = (n - 1) as f64 * classes.total as f64;
    let chi_candidates = chi2(&candidates, &|i, j| (m[i] + m[j]) as f64 / total_m);
    eprintln!(
        "chi2 (27 dof): collisions {chi_collisions:.1}, candidates {chi_candidates:.1}; \
         mean waiting time {mean_time:.5} vs {expected_time:.5} +- {time_error:.5}; \
         candidates per collision {per_collision:.4} vs {:.4} +- {per_collision_error:.4}",
        1.0 / p
    );
    assert!(chi_collisions < 65.0, "{chi_collisions}");
    assert!(chi_candidates < 65.0, "{chi_candidates}");
    assert!((mean_time - expected_time).abs() < 5.0 * time_error);
    assert!((per_collision - 1.0 / p).abs() < 5.0 * per_collision_error);
}

/// The class process against the kernel's single-majorant process (the scheme it
/// replaces), the same master equation: a cooling gas of 200 particles (eps = 0.7, a
/// hot particle) run to a fixed time of about 5 collisions per particle, 300 seeds each;
/// the mean temperature and collision count agree within 4 combined standard errors
/// (errors from the spread over seeds), and the class process needs fewer than half the
/// candidates.
#[test]
fn class_process_agrees_with_the_single_majorant_process() {
    let n = 200;
    let law = Constant::new(0.7).unwrap();
    let (species, _) = Species::of::<3>(&vec![0.5; n], &vec![1.0; n], 0.1).unwrap();
    let collider = Collider {
        rough: None,
        law: &law,
        species: &species,
        pairs: None,
    };
    let reference = [0.0; 3];
    let pair_rate = 0.025;
    let window = Window {
        start: 0.0,
        end: 1.0,
        max_collisions: u64::MAX,
    };
    let temperature = |g: &[Vector<3>]| g.iter().map(|v| dot(v, v)).sum::<f64>() / (3 * n) as f64;
    let mean_error = |x: &[f64]| {
        let mean = x.iter().sum::<f64>() / x.len() as f64;
        let var = x.iter().map(|y| (y - mean).powi(2)).sum::<f64>() / (x.len() - 1) as f64;
        (mean, (var / x.len() as f64).sqrt())
    };
    let mut results = vec![];
    for classed in [false, true] {
        let (mut t, mut c, mut candidates) = (vec![], vec![], 0);
        for seed in 0..300 {
            let mut group = maxwellian(n, 1000 + seed);
            group[0] = [6.0, 0.0, 0.0];
            group[1] = [-6.0, 0.0, 0.0];
            let mut rng = Stream::new(seed, Purpose::Block, 7, 0);
            let mut tally = Counters::default();
            let mut bound = crate::dsmc::kernel::speed_bound(&group, &reference);
            if classed {
                let mut class = Vec::new();
                let width = class_width(temperature(&group), 1.0, bound);
                let mut k = Classes::sort(&mut group, &mut class, &reference, width, bound);
                collider.run_classes(
                    &mut group, &mut class, &mut k, &reference, pair_rate, window, &mut rng,
                    &mut tally,
                );
            } else {
                collider.run(
                    &mut group, &reference, pair_rate, window, &mut bound, &mut rng, &mut tally,
                );
            }
            t.push(temperature(&group));
            c.push(tally.collisions as f64);
            candidates += tally.events;
        }
        let per_collision = candidates as f64 / c.iter().sum::<f64>();
        results.push((mean_error(&t), mean_error(&c), per_collision));
    }
    let [(t0, c0, k0), (t1, c1, k1)] = [results[0], results[1]];
    eprintln!(
        "single majorant: T {:.5} +- {:.5}, collisions {:.2} +- {:.2}, {k0:.3} candidates \
         per collision; classes: T {:.5} +- {:.5}, collisions {:.2} +- {:.2}, {k1:.3}",
        t0.0, t0.1, c0.0, c0.1, t1.0, t1.1, c1.0, c1.1
    );
    assert!(c0.0 > 2.0 * n as f64, "{c0:?}");
    assert!((t0.0 - t1.0).abs() < 4.0 * t0.1.hypot(t1.1));
    assert!((c0.0 - c1.0).abs() < 4.0 * c0.1.hypot(c1.1));
    assert!(k1 < 0.5 * k0, "{k0} {k1}");
}
