//! One rod of Eq. (2) of Giese: centre of mass (R, P) and free-free cosine modes.
//!
//! Modes are stored as `q` and `y = p/(m ω)`, so that free flight is a pure rotation
//! of (q, y) by the angle ω t and the modal energy is m ω² (q² + y²)/2. Internally
//! the modes are split by parity (odd ν first, then even ν) because the end
//! displacements are u(−l/2) = √2 Σ q_ν and u(+l/2) = √2 Σ (−1)^ν q_ν: with the
//! split both are plain sums and the contact kick is a constant per half.

use std::f64::consts::{PI, SQRT_2};

/// State and constants of one rod (lazy clock `t`: the state is valid at time `t`).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct Rod {
    pub len: f64,
    pub mass: f64,
    /// Time at which `x`, `v`, `q`, `y` are valid.
    pub t: f64,
    pub x: f64,
    pub v: f64,
    /// Number of odd modes (stored first).
    pub n_odd: usize,
    pub omega: Vec<f64>,
    /// √2/(m ω): converts a contact impulse into a change of `y`.
    pub gain: Vec<f64>,
    pub q: Vec<f64>,
    pub y: Vec<f64>,
    /// Cached free-flight invariants (D, S) of `end_bounds`; cleared by kicks.
    pub bounds: Option<(f64, f64)>,
}

impl Rod {
    /// Cold rod with `modes` modes, ω_ν = ν π c / l.
    pub fn new(len: f64, rho: f64, c: f64, modes: usize, x: f64, v: f64) -> Rod {
        let mass = rho * len;
        let n_odd = modes.div_ceil(2);
        let omega: Vec<f64> = (0..modes)
            .map(|j| nu_of(j, n_odd) as f64 * PI * c / len)
            .collect();
        let gain = omega.iter().map(|w| SQRT_2 / (mass * w)).collect();
        Rod {
            len,
            mass,
            t: 0.0,
            x,
            v,
            n_odd,
            omega,
            gain,
            q: vec![0.0; modes],
            y: vec![0.0; modes],
            bounds: None,
        }
    }

    /// Internal index of mode ν (1-based).
    pub fn index_of(&self, nu: usize) -> usize {
        if nu % 2 == 1 {
            nu / 2
        } else {
            self.n_odd + nu / 2 - 1
        }
    }

    /// End displacements (u(−l/2), u(+l/2)).
    pub fn ends(&self) -> (f64, f64) {
        let so = sum4(&self.q[..self.n_odd]);
        let se = sum4(&self.q[self.n_odd..]);
        (SQRT_2 * (so + se), SQRT_2 * (se - so))
    }

    /// Exact free flight to time `t` (translation linear, each mode rotated by ω Δt).
    pub fn drift_to(&mut self, t: f64) {
        let dt = t - self.t;
        if dt == 0.0 {
            return;
        }
        self.x += self.v * dt;
        for ((q, y), w) in self.q.iter_mut().zip(self.y.iter_mut()).zip(&self.omega) {
            let (s, c) = (w * dt).sin_cos();
            let (q0, y0) = (*q, *y);
            *q = c * q0 + s * y0;
            *y = c * y0 - s * q0;
        }
        self.t = t;
    }

    /// `kick(dt, fl, fr)` followed by the exact free flight over the cluster step h
    /// (cs, sn = cos, sin of ω h), returning the new end displacements. One pass over
    /// the modes; the end sums are a separate loop so that both vectorize (a running
    /// sum would serialize on floating-point latency).
    pub fn kick_drift(
        &mut self,
        dt: f64,
        fl: f64,
        fr: f64,
        h: f64,
        cs: &[f64],
        sn: &[f64],
    ) -> (f64, f64) {
        self.bounds = None;
        self.v += dt * (fl - fr) / self.mass;
        self.x += self.v * h;
        let n = self.n_odd;
        for (range, k) in [(0..n, dt * (fl + fr)), (n..self.q.len(), dt * (fl - fr))] {
            let it = self.q[range.clone()]
                .iter_mut()
                .zip(self.y[range.clone()].iter_mut());
            let coef = self.gain[range.clone()]
                .iter()
                .zip(&cs[range.clone()])
                .zip(&sn[range]);
            for ((q, y), ((g, c), s)) in it.zip(coef) {
                let (q0, y0) = (*q, *y + k * g);
                *q = c * q0 + s * y0;
                *y = c * y0 - s * q0;
            }
        }
        let so = sum4(&self.q[..n]);
        let se = sum4(&self.q[n..]);
        (SQRT_2 * (so + se), SQRT_2 * (se - so))
    }

    /// Contact kick over `dt` with force `fl` on the left end (from contact i−1,
    /// pushing towards +x) and `fr` on the right end (contact i, pushing towards −x):
    /// dP/dt = fl − fr, dp_ν/dt = √2 (fl − (−1)^ν fr).
    pub fn kick(&mut self, dt: f64, fl: f64, fr: f64) {
        self.bounds = None;
        self.v += dt * (fl - fr) / self.mass;
        let (go, ge) = self.gain.split_at(self.n_odd);
        let (yo, ye) = self.y.split_at_mut(self.n_odd);
        let (ko, ke) = (dt * (fl + fr), dt * (fl - fr));
        for (y, g) in yo.iter_mut().zip(go) {
            *y += ko * g;
        }
        for (y, g) in ye.iter_mut().zip(ge) {
            *y += ke * g;
        }
    }

    /// Energy of mode at internal index `j`: p²/2m + m ω² q²/2.
    pub fn mode_energy(&self, j: usize) -> f64 {
        let w = self.omega[j];
        0.5 * self.mass * w * w * (self.q[j] * self.q[j] + self.y[j] * self.y[j])
    }

    /// Translational plus modal energy.
    pub fn energy(&self) -> f64 {
        let modal: f64 = (0..self.q.len()).map(|j| self.mode_energy(j)).sum();
        0.5 * self.mass * self.v * self.v + modal
    }

    /// Free-flight invariants bounding the end motion: D = √2 Σ A_ν bounds |u_end|,
    /// S = √2 Σ ω A_ν bounds |du_end/dt| (A_ν = √(q² + y²) is constant in free flight).
    pub fn end_bounds(&mut self) -> (f64, f64) {
        if let Some(b) = self.bounds {
            return b;
        }
        let mut d = 0.0;
        let mut s = 0.0;
        for ((q, y), w) in self.q.iter().zip(&self.y).zip(&self.omega) {
            let a = q.hypot(*y);
            d += a;
            s += w * a;
        }
        let b = (SQRT_2 * d, SQRT_2 * s);
        self.bounds = Some(b);
        b
    }

    /// Centre and end displacements (x, u_left, u_right) at time `t` in free flight,
    /// without changing the state (so repeated checks accumulate no rounding in it).
    /// Uses ω_ν = ν ω_1: cos/sin of ν θ by complex recurrence (error ~ ν ε).
    pub fn ends_at(&self, t: f64) -> (f64, f64, f64) {
        let dt = t - self.t;
        if dt == 0.0 {
            let (ul, ur) = self.ends();
            return (self.x, ul, ur);
        }
        let th = self.omega[0] * dt;
        let (s1, c1) = th.sin_cos();
        let (s2, c2) = (2.0 * th).sin_cos();
        let mut sums = [0.0f64; 2];
        let n = self.n_odd;
        for (k, (range, start)) in [(0..n, (c1, s1)), (n..self.q.len(), (c2, s2))]
            .into_iter()
            .enumerate()
        {
            let (mut c, mut s) = start;
            let mut acc = 0.0;
            for (q, y) in self.q[range.clone()].iter().zip(&self.y[range]) {
                acc += c * q + s * y;
                (c, s) = (c * c2 - s * s2, s * c2 + c * s2);
            }
            sums[k] = acc;
        }
        let x = self.x + self.v * dt;
        (
            x,
            SQRT_2 * (sums[0] + sums[1]),
            SQRT_2 * (sums[1] - sums[0]),
        )
    }
}

/// Mode number ν of internal index `j` (odd ν first).
pub(crate) fn nu_of(j: usize, n_odd: usize) -> usize {
    if j < n_odd {
        2 * j + 1
    } else {
        2 * (j - n_odd) + 2
    }
}

/// Sum with four independent accumulators (vectorizes).
fn sum4(x: &[f64]) -> f64 {
    let mut acc = [0.0f64; 4];
    let chunks = x.chunks_exact(4);
    let rest: f64 = chunks.remainder().iter().sum();
    for c in chunks {
        for k in 0..4 {
            acc[k] += c[k];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + rest
}
