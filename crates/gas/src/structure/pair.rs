//! The static structure factor S(k) and the pair correlation g(r).
//!
//! S(k) = <|ρ_k|²> / N on the wave vectors of the box, by FFT: the particles are assigned to
//! a G^D grid by cloud-in-cell (CIC) weights, the grid is Fourier transformed (rustfft), and
//! the CIC window W(n) = Π_a sinc²(π n_a / G) and its aliases are corrected with the
//! shot-noise form of Jing (ApJ 620, 559 (2005)): |ρ̂(n)|²/N = W² S(k) + Σ_{m≠0} W²(n + mG),
//! Σ_m W²(n + mG) = Π_a (1 − (2/3) sin²(π n_a / G)), assuming S = 1 at the aliased wave
//! numbers (beyond the fluid's structure). Wave vectors up to half the grid's Nyquist number
//! (|n| ≤ G/4) are kept and averaged in shells of unit width in |n|.
//!
//! g(r) by counting pairs with cell lists (minimum image), normalized by the ideal-gas count
//! N n V_D (r₂^D − r₁^D).

use crate::system::{ball_volume, wrap, System};
use rayon::prelude::*;
use rustfft::num_complex::Complex64;
use rustfft::FftPlanner;
use std::f64::consts::PI;

/// One point of S(k) or g(r): the argument, the value and the number of wave vectors (pairs
/// of the ideal gas for g) behind it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StructurePoint {
    pub x: f64,
    pub value: f64,
    pub count: f64,
}

/// The multi-dimensional FFT of `data` (G^D, x fastest) in place, axis by axis.
fn fft_in_place<const D: usize>(data: &mut [Complex64], g: usize) {
    let fft = FftPlanner::new().plan_fft_forward(g);
    // the first axis is contiguous: transform its lines in place
    data.par_chunks_mut(g).for_each(|line| fft.process(line));
    for axis in 1..D {
        let stride = g.pow(axis as u32);
        let lines = data.len() / g;
        // gather each line along `axis`, transform, scatter back
        let starts: Vec<usize> = (0..lines)
            .map(|l| {
                let low = l % stride;
                let high = l / stride;
                low + high * stride * g
            })
            .collect();
        let transformed: Vec<Vec<Complex64>> = starts
            .par_iter()
            .map(|&s| {
                let mut line: Vec<Complex64> = (0..g).map(|i| data[s + i * stride]).collect();
                fft.process(&mut line);
                line
            })
            .collect();
        for (&s, line) in starts.iter().zip(transformed) {
            for (i, v) in line.into_iter().enumerate() {
                data[s + i * stride] = v;
            }
        }
    }
}

/// S(k) of `system` on a `grid`^D FFT grid (see the module documentation), for k up to
/// 2π (grid/4) / L.
pub fn structure_factor<const D: usize>(system: &System<D>, grid: usize) -> Vec<StructurePoint> {
    let g = grid;
    let h = system.length / g as f64;
    let mut rho = vec![Complex64::new(0.0, 0.0); g.pow(D as u32)];
    for r in &system.positions {
        // CIC: the 2^D nearest grid points with linear weights
        let mut base = [0usize; D];
        let mut frac = [0.0f64; D];
        for a in 0..D {
            let x = wrap(r[a], system.length) / h;
            let i = x.floor();
            base[a] = i as usize % g;
            frac[a] = x - i;
        }
        for corner in 0..(1usize << D) {
            let (mut index, mut weight, mut stride) = (0, 1.0, 1);
            for a in 0..D {
                let up = (corner >> a) & 1;
                index += ((base[a] + up) % g) * stride;
                weight *= if up == 1 { frac[a] } else { 1.0 - frac[a] };
                stride *= g;
            }
            rho[index].re += weight;
        }
    }
    fft_in_place::<D>(&mut rho, g);
    let n = system.len() as f64;
    let max_shell = g / 4;
    // per axis and grid index: (m, sinc⁴(π m / G), 1 − (2/3) sin²(π m / G)), m the signed
    // wave number; entries with |m| > G/4 on any axis lie outside every kept shell
    let axis: Vec<(i64, f64, f64)> = (0..g)
        .map(|i| {
            let m = if i > g / 2 {
                i as i64 - g as i64
            } else {
                i as i64
            };
            let x = PI * m as f64 / g as f64;
            let sinc = if m == 0 { 1.0 } else { x.sin() / x };
            (m, sinc.powi(4), 1.0 - 2.0 / 3.0 * x.sin().powi(2))
        })
        .collect();
    let kept: Vec<usize> = (0..g)
        .filter(|&i| axis[i].0.unsigned_abs() as usize <= max_shell)
        .collect();
    let mut sums = vec![(0.0, 0.0, 0usize); max_shell + 1];
    for k in 0..kept.len().pow(D as u32) {
        let (mut f, mut flat, mut stride) = (k, 0, 1);
        let (mut norm2, mut window, mut alias) = (0usize, 1.0, 1.0);
        for _ in 0..D {
            let i = kept[f % kept.len()];
            f /= kept.len();
            flat += i * stride;
            stride *= g;
            let (m, w, a) = axis[i];
            norm2 += (m * m) as usize;
            window *= w;
            alias *= a;
        }
        let shell = (norm2 as f64).sqrt().round() as usize;
        if norm2 == 0 || shell > max_shell {
            continue;
        }
        let s = (rho[flat].norm_sqr() / n - (alias - window)) / window;
        let entry = &mut sums[shell];
        entry.0 += s;
        entry.1 += (norm2 as f64).sqrt();
        entry.2 += 1;
    }
    sums.iter()
        .filter(|e| e.2 > 0)
        .map(|&(s, norm, count)| StructurePoint {
            x: 2.0 * PI / system.length * norm / count as f64,
            value: s / count as f64,
            count: count as f64,
        })
        .collect()
}

/// g(r) of `system` in `bins` bins on [0, r_max) (r_max ≤ L/2), by cell lists.
pub fn pair_correlation<const D: usize>(
    system: &System<D>,
    r_max: f64,
    bins: usize,
) -> Vec<StructurePoint> {
    let l = system.length;
    let r_max = r_max.min(0.5 * l);
    let cells = ((l / r_max).floor() as usize).max(1);
    let width = l / cells as f64;
    let cell_of = |r: &[f64; D]| -> [usize; D] {
        std::array::from_fn(|a| ((wrap(r[a], l) / width) as usize).min(cells - 1))
    };
    let flat = |c: &[usize; D]| c.iter().rev().fold(0, |s, &x| s * cells + x);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); cells.pow(D as u32)];
    for (i, r) in system.positions.iter().enumerate() {
        members[flat(&cell_of(r))].push(i);
    }
    // neighbour offsets: all cells when there are fewer than 3 per side (each once)
    let reach: Vec<i64> = if cells >= 3 {
        vec![-1, 0, 1]
    } else {
        (0..cells as i64).collect()
    };
    let dr = r_max / bins as f64;
    let counts = (0..members.len())
        .into_par_iter()
        .fold(
            || vec![0u64; bins],
            |mut acc, cell| {
                let mut c = [0usize; D];
                let mut f = cell;
                for x in c.iter_mut() {
                    *x = f % cells;
                    f /= cells;
                }
                for offset in 0..reach.len().pow(D as u32) {
                    let mut o = offset;
                    let other: [usize; D] = std::array::from_fn(|a| {
                        let step = reach[o % reach.len()];
                        o /= reach.len();
                        if cells >= 3 {
                            (c[a] as i64 + step).rem_euclid(cells as i64) as usize
                        } else {
                            step as usize
                        }
                    });
                    for &i in &members[cell] {
                        for &j in &members[flat(&other)] {
                            if i == j {
                                continue;
                            }
                            let s = system.separation(&system.positions[i], &system.positions[j]);
                            let r = s.iter().map(|x| x * x).sum::<f64>().sqrt();
                            if r < r_max {
                                acc[(r / dr) as usize] += 1;
                            }
                        }
                    }
                }
                acc
            },
        )
        .reduce(
            || vec![0u64; bins],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
                a
            },
        );
    let n = system.len() as f64;
    let density = n / system.volume();
    counts
        .iter()
        .enumerate()
        .map(|(b, &c)| {
            let (r1, r2) = (b as f64 * dr, (b + 1) as f64 * dr);
            let ideal = n * density * (ball_volume::<D>(r2) - ball_volume::<D>(r1));
            StructurePoint {
                x: 0.5 * (r1 + r2),
                value: c as f64 / ideal,
                count: ideal,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn random_system<const D: usize>(n: usize, length: f64, seed: u64) -> System<D> {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        System {
            length,
            positions: (0..n)
                .map(|_| std::array::from_fn(|_| rng.random::<f64>() * length))
                .collect(),
            velocities: vec![[0.0; D]; n],
            radii: vec![0.0; n],
            masses: vec![1.0; n],
        }
    }

    /// Uniform random points: S(k) = 1 and g(r) = 1. Each S bin averages `count` exponential
    /// variables (s.d. 1/sqrt(count)); each g bin is a Poisson count with s.d.
    /// 1/sqrt(ideal/2) (pairs counted twice). Five standard deviations.
    #[test]
    fn ideal_gas_is_structureless() {
        let s2 = random_system::<2>(20_000, 100.0, 1);
        for p in structure_factor(&s2, 128) {
            assert!(
                (p.value - 1.0).abs() < 5.0 / p.count.sqrt(),
                "2D S({}) = {}",
                p.x,
                p.value
            );
        }
        for p in pair_correlation(&s2, 5.0, 20) {
            assert!(
                (p.value - 1.0).abs() < 5.0 / (0.5 * p.count).sqrt(),
                "g({}) = {}",
                p.x,
                p.value
            );
        }
        let s3 = random_system::<3>(20_000, 30.0, 2);
        for p in structure_factor(&s3, 32) {
            assert!(
                (p.value - 1.0).abs() < 5.0 / p.count.sqrt(),
                "3D S({}) = {}",
                p.x,
                p.value
            );
        }
        for p in pair_correlation(&s3, 3.0, 10) {
            assert!(
                (p.value - 1.0).abs() < 5.0 / (0.5 * p.count).sqrt(),
                "g({}) = {}",
                p.x,
                p.value
            );
        }
    }

    /// FFT S(k) against the direct sum |Σ e^{−ik·r}|²/N over the same wave vectors (those
    /// with round(|n|) = 1, 2) for one configuration. The grid's errors are O((π|n|/G)²) ~ 1e-3
    /// there; tolerance 1 %.
    #[test]
    fn fft_agrees_with_the_direct_sum_at_small_k() {
        let s = random_system::<2>(5000, 50.0, 3);
        let fft = structure_factor(&s, 256);
        let shells = super::super::fourier::half_space_shells::<2>(6);
        for bin in [1usize, 2] {
            let vectors: Vec<[i32; 2]> = shells
                .iter()
                .filter(|sh| (sh.norm2 as f64).sqrt().round() as usize == bin)
                .flat_map(|sh| sh.vectors.clone())
                .collect();
            let amp = super::super::fourier::fourier_amplitudes(&s, &vectors);
            let direct = amp.density.iter().map(|c| c.norm_sqr()).sum::<f64>()
                / (vectors.len() * s.len()) as f64;
            let f = fft[bin - 1];
            assert_eq!(f.count as usize, 2 * vectors.len());
            assert!(
                (f.value - direct).abs() < 0.01 * direct,
                "bin {bin}: {} vs {direct}",
                f.value
            );
        }
    }

    /// A square lattice: g(r) has its first peak at the lattice constant.
    #[test]
    fn lattice_peak() {
        let side = 30;
        let positions: Vec<[f64; 2]> = (0..side * side)
            .map(|i| [(i % side) as f64 + 0.5, (i / side) as f64 + 0.5])
            .collect();
        let n = positions.len();
        let s = System::<2> {
            length: side as f64,
            positions,
            velocities: vec![[0.0; 2]; n],
            radii: vec![0.0; n],
            masses: vec![1.0; n],
        };
        let g = pair_correlation(&s, 3.0, 30);
        let peak = g.iter().max_by(|a, b| a.value.total_cmp(&b.value)).unwrap();
        assert!((peak.x - 1.05).abs() < 0.051, "{peak:?}");
        // 4 neighbours at r = 1 in the bin [1.0, 1.1): count 4 per particle
        let expected = 4.0 / ((n as f64 / (side * side) as f64) * PI * (1.1f64.powi(2) - 1.0));
        assert!((peak.value - expected).abs() < 1e-9 * expected);
    }
}
