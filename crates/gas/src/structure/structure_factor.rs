//! The static structure factor S(k) = <|ρ_k|²> / N on the wave vectors of the box, by FFT.
//!
//! The particles are assigned to a G^D grid by cloud-in-cell (CIC) weights, the grid is
//! Fourier transformed, and the CIC window W(n) = Π_a sinc²(π n_a / G) and its aliases are
//! corrected with the shot-noise form of Jing (ApJ 620, 559 (2005)):
//! |ρ̂(n)|²/N = W² S(k) + Σ_{m≠0} W²(n + mG), Σ_m W²(n + mG) = Π_a (1 − (2/3) sin²(π n_a / G)),
//! assuming S = 1 at the aliased wave numbers (beyond the fluid's structure). Wave vectors up
//! to half the grid's Nyquist number (|n_a| ≤ K = G/4 on every axis, round(|n|) ≤ K) are kept
//! and averaged in shells of unit width in |n|.
//!
//! Only those (2K + 1)^D ≈ 2^−D G^D amplitudes are computed, which makes the transform cheap
//! enough to run at every sample (issue 16: at most 10 % of one collision per particle of
//! event-driven MD; `haff bench observers`):
//!
//! - the grid is real, so axis 0 is transformed real-to-complex (`realfft`) and only
//!   0 ≤ n_0 ≤ K is kept; n_0 < 0 follows from ρ̂(−n) = ρ̂(n)*, so those wave vectors count
//!   twice in the shell averages;
//! - each later axis is transformed only on the lines that still matter (n_b kept on the
//!   axes b before it), and only |n_a| ≤ K is kept;
//! - the grid is never built whole: it is deposited slab by slab along the last axis (the
//!   particles sorted by slab beforehand), each slab transformed on its own axes in cache,
//!   in parallel; the slabs' results are transposed into contiguous lines for the last axis
//!   (rustfft transforms many contiguous lines in one call), never gathered element by
//!   element.
//!
//! Every slab and line is computed the same way whatever the thread that does it, and the
//! shell sums run in a fixed order, so the result does not depend on the thread count (a
//! resumed run writes the same bits).

use super::pair::StructurePoint;
use crate::system::{wrap, System};
use rayon::prelude::*;
use realfft::{RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::f64::consts::PI;
use std::ops::Range;
use std::sync::Arc;

/// S(k) of `system` on a `grid`^D FFT grid (see the module documentation), for k up to
/// 2π (grid/4) / L.
pub fn structure_factor<const D: usize>(system: &System<D>, grid: usize) -> Vec<StructurePoint> {
    let max_shell = grid / 4;
    let amplitudes = LowModes::<D>::new(grid).amplitudes(system);
    let n = system.len() as f64;
    let width = 2 * max_shell + 1;
    // per signed wave number m (at m + K): sinc⁴(π m / G) and 1 − (2/3) sin²(π m / G)
    let axis: Vec<(f64, f64)> = (0..width)
        .map(|p| {
            let m = p as i64 - max_shell as i64;
            let x = PI * m as f64 / grid as f64;
            let sinc = if m == 0 { 1.0 } else { x.sin() / x };
            (sinc.powi(4), 1.0 - 2.0 / 3.0 * x.sin().powi(2))
        })
        .collect();
    let squares: Vec<usize> = (0..width).map(|p| p.abs_diff(max_shell).pow(2)).collect();
    let plane = width.pow(D as u32 - 1);
    // one partial sum per n_0 (summed in the order of n_0 below): (S, |n|, wave vectors)
    let partial: Vec<Vec<(f64, f64, usize)>> = amplitudes
        .par_chunks(plane)
        .enumerate()
        .map(|(n0, chunk)| {
            let mut sums = vec![(0.0, 0.0, 0usize); max_shell + 1];
            // n and −n for n_0 > 0; the plane n_0 = 0 holds both already
            let multiplicity = if n0 == 0 { 1 } else { 2 };
            // positions on the axes (m_a = p_a − K), the last fastest, counted up in step
            // with the chunk (no division per wave vector)
            let mut next = [0usize; D];
            next[0] = n0 + max_shell;
            for rho in chunk {
                let p = next;
                for a in (1..D).rev() {
                    next[a] += 1;
                    if next[a] < width {
                        break;
                    }
                    next[a] = 0;
                }
                let norm2: usize = p.iter().map(|&pa| squares[pa]).sum();
                // round(|n|) ≤ K exactly when |n|² ≤ K² + K (integers)
                if norm2 == 0 || norm2 > max_shell * (max_shell + 1) {
                    continue;
                }
                let (mut window, mut alias) = (1.0, 1.0);
                for &pa in &p {
                    window *= axis[pa].0;
                    alias *= axis[pa].1;
                }
                let norm = (norm2 as f64).sqrt();
                // round(|n|) without the library call: |n| of an integer vector n is never
                // within 0.1/|n| of a half-integer, far above round-off
                let shell = (norm + 0.5) as usize;
                let s = (rho.norm_sqr() / n - (alias - window)) / window;
                let entry = &mut sums[shell];
                entry.0 += multiplicity as f64 * s;
                entry.1 += multiplicity as f64 * norm;
                entry.2 += multiplicity;
            }
            sums
        })
        .collect();
    let mut sums = vec![(0.0, 0.0, 0usize); max_shell + 1];
    for part in partial {
        for (total, (s, norm, count)) in sums.iter_mut().zip(part) {
            total.0 += s;
            total.1 += norm;
            total.2 += count;
        }
    }
    shell_means(
        &sums,
        crate::structure::cube_side(system, "the structure factor"),
    )
}

/// The points of the occupied shells from their sums (S, |n|, count): mean k and mean S.
fn shell_means(sums: &[(f64, f64, usize)], length: f64) -> Vec<StructurePoint> {
    sums.iter()
        .filter(|e| e.2 > 0)
        .map(|&(s, norm, count)| StructurePoint {
            x: 2.0 * PI / length * norm / count as f64,
            value: s / count as f64,
            count: count as f64,
        })
        .collect()
}

/// Lines transformed per call of the last axis's FFT (a fixed blocking: the same
/// arithmetic whatever the thread count).
const LINES_PER_BLOCK: usize = 16;

/// The plans of the pruned transform on a G^D grid, keeping |n_a| ≤ K = G/4.
struct LowModes<const D: usize> {
    grid: usize,
    max_shell: usize,
    real: Arc<dyn RealToComplex<f64>>,
    complex: Arc<dyn Fft<f64>>,
}

impl<const D: usize> LowModes<D> {
    fn new(grid: usize) -> Self {
        LowModes {
            grid,
            max_shell: grid / 4,
            real: RealFftPlanner::<f64>::new().plan_fft_forward(grid),
            complex: FftPlanner::new().plan_fft_forward(grid),
        }
    }

    /// Kept wave numbers on axes 1..: 2K + 1.
    fn width(&self) -> usize {
        2 * self.max_shell + 1
    }

    /// The CIC grid's amplitudes ρ̂(n) for 0 ≤ n_0 ≤ K and |n_a| ≤ K (a ≥ 1), laid out with
    /// n_0 slowest and n_{D−1} fastest, m_a = n_a + K the position on axes a ≥ 1.
    fn amplitudes(&self, system: &System<D>) -> Vec<Complex64> {
        let g = self.grid;
        let deposits = Deposits::new(system, g);
        if D == 1 {
            let mut line = vec![0.0; g];
            deposits.deposit_plane(&mut line, 0..system.len(), None);
            let mut spectrum = self.real.make_output_vec();
            self.real
                .process(&mut line, &mut spectrum)
                .expect("buffer lengths from the plan");
            spectrum.truncate(self.max_shell + 1);
            return spectrum;
        }
        // each slab along the last axis: its axes 0..D−1 transformed, [n_0][n_1]..[n_{D−2}]
        let per_slab = (self.max_shell + 1) * self.width().pow(D as u32 - 2);
        let mut slabs = vec![Complex64::new(0.0, 0.0); g * per_slab];
        slabs.par_chunks_mut(per_slab).enumerate().for_each_init(
            || SlabBuffers::new(self, g.pow(D as u32 - 1)),
            |buffers, (slab, out)| self.slab_modes(&deposits, slab, buffers, out),
        );
        // the last axis: [G][per_slab] → [per_slab][2K + 1]
        self.transform_middle_axis(&slabs, 1, per_slab, true)
    }

    /// The transformed slab `slab` (index on the last axis) into `out`.
    fn slab_modes(
        &self,
        deposits: &Deposits<D>,
        slab: usize,
        buffers: &mut SlabBuffers,
        out: &mut [Complex64],
    ) {
        let g = self.grid;
        let plane = &mut buffers.plane;
        plane.fill(0.0);
        // the slab holds the particles based in it (weight 1 − f on the last axis) and those
        // based in the slab before (weight f)
        deposits.deposit_plane(plane, deposits.in_slab(slab), Some(false));
        deposits.deposit_plane(plane, deposits.in_slab((slab + g - 1) % g), Some(true));
        // axis 0, real to complex, 0 ≤ n_0 ≤ K kept: [rows][K + 1]
        let kept0 = self.max_shell + 1;
        let rows = g.pow(D as u32 - 2);
        let mut data = std::mem::take(&mut buffers.rows);
        data.clear();
        for row in plane.chunks_exact_mut(g) {
            self.real
                .process_with_scratch(row, &mut buffers.spectrum, &mut buffers.real_scratch)
                .expect("buffer lengths from the plan");
            data.extend_from_slice(&buffers.spectrum[..kept0]);
        }
        // axes 1..D−1: [outer][G][inner] → [outer][inner][2K + 1]
        let mut inner = kept0;
        for axis in 1..D - 1 {
            let outer = rows / g.pow(axis as u32);
            data = self.transform_middle_axis(&data, outer, inner, false);
            inner *= self.width();
        }
        out.copy_from_slice(&data);
        buffers.rows = data;
    }

    /// `data` laid out as [outer][G][inner], transformed along its middle axis with only
    /// |n| ≤ K kept: [outer][inner][2K + 1]. Blocks of lines are copied into contiguous
    /// lines (a transpose: each row of a block is a contiguous run of `data`) and
    /// transformed in one call; `parallel` spreads the blocks over the threads.
    fn transform_middle_axis(
        &self,
        data: &[Complex64],
        outer: usize,
        inner: usize,
        parallel: bool,
    ) -> Vec<Complex64> {
        let (g, k, width) = (self.grid, self.max_shell, self.width());
        let lines = outer * inner;
        let mut out = vec![Complex64::new(0.0, 0.0); lines * width];
        let block = |buffers: &mut LineBuffers, (b, out): (usize, &mut [Complex64])| {
            let first = b * LINES_PER_BLOCK;
            let count = out.len() / width;
            let lines = &mut buffers.lines[..count * g];
            for (l, line) in lines.chunks_exact_mut(g).enumerate() {
                let (o, j) = ((first + l) / inner, (first + l) % inner);
                let column = &data[o * g * inner + j..];
                for (i, x) in line.iter_mut().enumerate() {
                    *x = column[i * inner];
                }
            }
            self.complex
                .process_with_scratch(lines, &mut buffers.scratch);
            for (line, kept) in lines.chunks_exact(g).zip(out.chunks_exact_mut(width)) {
                // n = −K..−1 at the end of the line, then 0..K
                kept[..k].copy_from_slice(&line[g - k..]);
                kept[k..].copy_from_slice(&line[..=k]);
            }
        };
        let init = || LineBuffers {
            lines: vec![Complex64::new(0.0, 0.0); LINES_PER_BLOCK * g],
            scratch: vec![Complex64::new(0.0, 0.0); self.complex.get_inplace_scratch_len()],
        };
        let chunk = LINES_PER_BLOCK * width;
        if parallel {
            out.par_chunks_mut(chunk)
                .enumerate()
                .for_each_init(init, block);
        } else {
            let mut buffers = init();
            out.chunks_mut(chunk)
                .enumerate()
                .for_each(|item| block(&mut buffers, item));
        }
        out
    }
}

/// Work space of one slab.
struct SlabBuffers {
    plane: Vec<f64>,
    rows: Vec<Complex64>,
    spectrum: Vec<Complex64>,
    real_scratch: Vec<Complex64>,
}

impl SlabBuffers {
    fn new<const D: usize>(plans: &LowModes<D>, plane: usize) -> Self {
        SlabBuffers {
            plane: vec![0.0; plane],
            rows: Vec::new(),
            spectrum: plans.real.make_output_vec(),
            real_scratch: plans.real.make_scratch_vec(),
        }
    }
}

/// Work space of one block of lines.
struct LineBuffers {
    lines: Vec<Complex64>,
    scratch: Vec<Complex64>,
}

/// The particles' CIC cells and weights, sorted by their cell on the last axis (in the
/// order of the particles within a slab).
struct Deposits<const D: usize> {
    grid: usize,
    /// Lower grid point and the fraction towards the upper one, per axis.
    cells: Vec<([usize; D], [f64; D])>,
    /// Start of each slab's particles in `cells` (G + 1 entries).
    starts: Vec<usize>,
}

impl<const D: usize> Deposits<D> {
    fn new(system: &System<D>, grid: usize) -> Self {
        let g = grid;
        let length = crate::structure::cube_side(system, "the structure factor");
        let h = length / g as f64;
        let cic = |r: &[f64; D]| {
            let mut base = [0usize; D];
            let mut frac = [0.0f64; D];
            for a in 0..D {
                let x = wrap(r[a], length) / h;
                // x ≥ 0: truncation is the floor (which is a library call on baseline
                // x86-64), and x/h ≤ G so one subtraction is the remainder
                let i = x as usize;
                base[a] = if i >= g { i - g } else { i };
                frac[a] = x - i as f64;
            }
            (base, frac)
        };
        let unsorted: Vec<([usize; D], [f64; D])> = system.positions.iter().map(cic).collect();
        // counting sort by the last axis, stable
        let mut starts = vec![0usize; g + 1];
        for (base, _) in &unsorted {
            starts[base[D - 1] + 1] += 1;
        }
        for s in 0..g {
            starts[s + 1] += starts[s];
        }
        let mut next = starts.clone();
        let mut cells = vec![([0usize; D], [0.0; D]); unsorted.len()];
        for cell in unsorted {
            let slot = &mut next[cell.0[D - 1]];
            cells[*slot] = cell;
            *slot += 1;
        }
        Deposits {
            grid: g,
            cells,
            starts,
        }
    }

    /// Positions in `cells` of the particles based in slab `slab`.
    fn in_slab(&self, slab: usize) -> Range<usize> {
        self.starts[slab]..self.starts[slab + 1]
    }

    /// Adds the CIC weights of the particles at `particles` in `cells` to `plane`, the grid
    /// of axes 0..D−1 (x fastest). `upper` = Some(up) weighs the last axis too, by f if up
    /// else 1 − f (the plane is one slab); None deposits on all D axes (the plane is the
    /// whole grid).
    fn deposit_plane(&self, plane: &mut [f64], particles: Range<usize>, upper: Option<bool>) {
        let g = self.grid;
        let axes = if upper.is_some() { D - 1 } else { D };
        for (base, frac) in &self.cells[particles] {
            for corner in 0..(1usize << axes) {
                let (mut index, mut weight, mut stride) = (0, 1.0, 1);
                for a in 0..axes {
                    let up = (corner >> a) & 1;
                    index += ((base[a] + up) % g) * stride;
                    weight *= if up == 1 { frac[a] } else { 1.0 - frac[a] };
                    stride *= g;
                }
                if let Some(up) = upper {
                    let f = frac[D - 1];
                    weight *= if up { f } else { 1.0 - f };
                }
                plane[index] += weight;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::structure::test_points::random_system;

    /// The full transform: the CIC grid built whole in particle order, a complex FFT on every
    /// line of every axis (strided gathers), and every kept wave vector summed over both
    /// half spaces; the definition the pruned transform must reproduce.
    fn full_transform_structure_factor<const D: usize>(
        system: &System<D>,
        g: usize,
    ) -> Vec<StructurePoint> {
        let length = crate::structure::cube_side(system, "the structure factor");
        let h = length / g as f64;
        let mut rho = vec![Complex64::new(0.0, 0.0); g.pow(D as u32)];
        for r in &system.positions {
            let mut base = [0usize; D];
            let mut frac = [0.0f64; D];
            for a in 0..D {
                let x = wrap(r[a], length) / h;
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
        let fft = FftPlanner::new().plan_fft_forward(g);
        for axis in 0..D {
            let stride = g.pow(axis as u32);
            for l in 0..rho.len() / g {
                let start = l % stride + (l / stride) * stride * g;
                let mut line: Vec<Complex64> = (0..g).map(|i| rho[start + i * stride]).collect();
                fft.process(&mut line);
                for (i, v) in line.into_iter().enumerate() {
                    rho[start + i * stride] = v;
                }
            }
        }
        let max_shell = g / 4;
        let signed = |i: usize| {
            if i > g / 2 {
                i as i64 - g as i64
            } else {
                i as i64
            }
        };
        let mut sums = vec![(0.0, 0.0, 0usize); max_shell + 1];
        for (flat, value) in rho.iter().enumerate() {
            let (mut f, mut norm2, mut window, mut alias) = (flat, 0usize, 1.0, 1.0);
            let mut inside = true;
            for _ in 0..D {
                let m = signed(f % g);
                f /= g;
                inside &= m.unsigned_abs() as usize <= max_shell;
                let x = PI * m as f64 / g as f64;
                let sinc = if m == 0 { 1.0 } else { x.sin() / x };
                norm2 += (m * m) as usize;
                window *= sinc.powi(4);
                alias *= 1.0 - 2.0 / 3.0 * x.sin().powi(2);
            }
            let shell = (norm2 as f64).sqrt().round() as usize;
            if !inside || norm2 == 0 || shell > max_shell {
                continue;
            }
            let s = (value.norm_sqr() / system.len() as f64 - (alias - window)) / window;
            sums[shell].0 += s;
            sums[shell].1 += (norm2 as f64).sqrt();
            sums[shell].2 += 1;
        }
        shell_means(
            &sums,
            crate::structure::cube_side(system, "the structure factor"),
        )
    }

    fn assert_same(pruned: &[StructurePoint], full: &[StructurePoint], what: &str) {
        assert_eq!(pruned.len(), full.len(), "{what}");
        for (p, f) in pruned.iter().zip(full) {
            assert_eq!(p.count, f.count, "{what}");
            assert!((p.x - f.x).abs() <= 1e-13 * f.x, "{what}: {p:?} vs {f:?}");
            assert!(
                (p.value - f.value).abs() <= 1e-12 * f.value.abs().max(1.0),
                "{what}: {p:?} vs {f:?}"
            );
        }
    }

    /// The pruned transform (real-to-complex, half space, slabs) gives the full transform's
    /// S(k) to round-off, in 1, 2 and 3 dimensions, on grids of powers of two and others.
    #[test]
    fn pruned_transform_matches_the_full_transform() {
        fn check<const D: usize>(grids: [usize; 3], length: f64, seed: u64) {
            let s = random_system::<D>(3000, length, seed);
            for g in grids {
                assert_same(
                    &structure_factor(&s, g),
                    &full_transform_structure_factor(&s, g),
                    &format!("{D}D, G = {g}"),
                );
            }
        }
        check::<1>([8, 64, 100], 40.0, 7);
        check::<2>([8, 48, 64], 40.0, 8);
        check::<3>([8, 20, 32], 12.0, 9);
    }

    /// A crystal with clustered particles has S far from 1 at small k; the pruned transform
    /// follows the full one there too (large amplitudes, not only noise).
    #[test]
    fn pruned_transform_matches_with_structure() {
        let mut s = random_system::<3>(2000, 16.0, 10);
        for r in s.positions.iter_mut() {
            r[0] = (r[0] / 4.0).floor() * 4.0 + 0.01 * r[0];
        }
        assert_same(
            &structure_factor(&s, 32),
            &full_transform_structure_factor(&s, 32),
            "3D clustered",
        );
    }

    /// Uniform random points: S(k) = 1. Each bin averages `count` exponential variables
    /// (s.d. 1/sqrt(count)). Five standard deviations.
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
        let s3 = random_system::<3>(20_000, 30.0, 2);
        for p in structure_factor(&s3, 32) {
            assert!(
                (p.value - 1.0).abs() < 5.0 / p.count.sqrt(),
                "3D S({}) = {}",
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
        let shells = crate::structure::fourier::half_space_shells::<2>(6);
        for bin in [1usize, 2] {
            let vectors: Vec<[i32; 2]> = shells
                .iter()
                .filter(|sh| (sh.norm2 as f64).sqrt().round() as usize == bin)
                .flat_map(|sh| sh.vectors.clone())
                .collect();
            let amp = crate::structure::fourier::fourier_amplitudes(&s, &vectors);
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
}
