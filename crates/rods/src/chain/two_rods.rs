//! The two-rod experiment of Figs. 1 and 2 of Giese: N = 2 on a ring, centre-of-mass
//! frame, relative velocity −V0, cold modes, equal free gaps on both sides.
//!
//! Units: c = ρ = 1, l = 2 l1 l2/(l1 + l2) = 1, V0 = 1, α = κ, B = μ c²/(α l)² = μ/κ²,
//! so that κ = α l V0/c as in Giese and E0 = μ V0²/2 = μ/2.

use super::{Chain, ChainConfig, ChainStats};
use crate::error::{positive, Error, Result};
use rand::Rng;
use std::time::Instant;

/// Parameters of the two-rod experiment.
#[derive(Clone, Copy, Debug)]
pub struct TwoRodSetup {
    /// Length ratio γ = l1/l2.
    pub gamma: f64,
    /// κ = α l V0 / c.
    pub kappa: f64,
    /// Modes per rod.
    pub modes: usize,
    /// Initial free gap on each side, in units of l.
    pub gap: f64,
    /// Step constant of the integrator.
    pub c_h: f64,
}

/// State right after one collision.
#[derive(Clone, Debug)]
pub struct TwoRodRecord {
    /// 1-based collision number.
    pub collision: usize,
    /// Which end: contact 0 (rod 1 right, rod 2 left) or 1.
    pub contact: usize,
    /// Contact episodes making up this collision.
    pub episodes: usize,
    pub t_start: f64,
    pub t_end: f64,
    /// E_tr/E0 after the collision, E_tr = μ Ṙ_{21}²/2.
    pub e_tr: f64,
    /// ε = −v'/v of this collision.
    pub eps: f64,
    /// Normalized spectral entropy η = 1 − h/ln(2M).
    pub eta: f64,
    /// w_{i,ν} = E_{i,ν}/E_bath: rod 1 ν = 1..M, then rod 2.
    pub w: Vec<f64>,
    /// Time from the start of this collision to the start of the next one.
    pub span: f64,
    /// ∫ E_tr/E0 dt over `span` (contact episodes and free flights).
    pub etr_integral: f64,
}

impl TwoRodSetup {
    /// Rod lengths (l1, l2) with 2 l1 l2/(l1 + l2) = 1.
    pub fn lengths(&self) -> (f64, f64) {
        let g = self.gamma;
        (0.5 * (1.0 + g), 0.5 * (1.0 + g) / g)
    }

    /// Reduced mass μ (ρ = 1).
    pub fn mu(&self) -> f64 {
        let (a, b) = self.lengths();
        a * b / (a + b)
    }

    /// The chain at t = 0.
    pub fn chain(&self) -> Result<Chain> {
        positive("gamma", self.gamma)?;
        positive("kappa", self.kappa)?;
        let (l1, l2) = self.lengths();
        let mtot = l1 + l2;
        Chain::new(ChainConfig {
            lengths: vec![l1, l2],
            modes: self.modes,
            alpha: self.kappa,
            b: self.mu() / (self.kappa * self.kappa),
            c: 1.0,
            rho: 1.0,
            perimeter: l1 + l2 + 2.0 * self.gap,
            positions: vec![0.0, 0.5 * (l1 + l2) + self.gap],
            velocities: vec![l2 / mtot, -l1 / mtot],
            c_h: self.c_h,
            global_step: true,
        })
    }

    /// eps = −v'/v of one impact of the two rods when the modes of both start from the
    /// Boltzmann distribution at T_bath = E0 / `energy_ratio` (E0 = μ V0²/2 = μ/2): the
    /// Hamiltonian experiment that Giese's Eq. (3) with the noise of Eq. (5) models (his
    /// Markov approximation is exact for one collision). One impact may open and close its
    /// contact several times; it ends when the other end's contact opens (the relative
    /// velocity is constant in free flight), at the latest after `MAX_EPISODES`.
    pub fn thermal_impact_eps<R: Rng + ?Sized>(
        &self,
        energy_ratio: f64,
        rng: &mut R,
    ) -> Result<f64> {
        const MAX_EPISODES: usize = 100_000;
        positive("energy_ratio", energy_ratio)?;
        let mut chain = self.chain()?;
        chain.thermalize_modes(0.5 * self.mu() / energy_ratio, rng)?;
        let mut next = |collisions: usize| {
            chain
                .run_collisions(1)
                .into_iter()
                .next()
                .ok_or(Error::NoFurtherCollision { collisions })
        };
        let first = next(0)?;
        let mut last = first;
        for episode in 1..MAX_EPISODES {
            let record = next(episode)?;
            if record.contact != first.contact {
                return Ok(-last.v_post / first.v_pre);
            }
            last = record;
        }
        Err(Error::NoFurtherCollision {
            collisions: MAX_EPISODES,
        })
    }
}

/// η = 1 − h/ln(n), h = −Σ w ln w, for relative energies `w` (Σ w = 1) of n modes.
pub fn spectral_entropy(w: &[f64]) -> f64 {
    let h: f64 = w.iter().filter(|&&x| x > 0.0).map(|&x| -x * x.ln()).sum();
    1.0 - h / (w.len() as f64).ln()
}

/// Mean of η for Dirichlet(1, …, 1) weights on n = 2M modes (microcanonical
/// Boltzmann): 1 − (H_n − 1)/ln n, H_n the harmonic number; ≈ 0.4228/ln(2M).
pub fn eta_equilibrium(modes: usize) -> f64 {
    let n = 2 * modes;
    let h_n: f64 = (1..=n).map(|k| 1.0 / k as f64).sum();
    1.0 - (h_n - 1.0) / (n as f64).ln()
}

fn snapshot(chain: &Chain, setup: &TwoRodSetup) -> (f64, f64, Vec<f64>) {
    let v = chain.velocities();
    let e0 = 0.5 * setup.mu();
    let mut modal = chain.modal_energies(0);
    modal.extend(chain.modal_energies(1));
    let bath: f64 = modal.iter().sum();
    let w: Vec<f64> = modal.iter().map(|e| e / bath).collect();
    let e_tr = 0.5 * setup.mu() * (v[1] - v[0]).powi(2) / e0;
    (e_tr, spectral_entropy(&w), w)
}

/// Result of [`run_two_rods`].
#[derive(Clone, Debug)]
pub struct TwoRodRun {
    /// Modes per rod.
    pub modes: usize,
    /// The transient: collisions before the time integrals (and [`TwoRodRun::summary`]'s
    /// means) start.
    pub skip: usize,
    /// One record per collision.
    pub records: Vec<TwoRodRecord>,
    /// Wall-clock seconds of the run.
    pub wall_seconds: f64,
    /// Cost counters.
    pub stats: ChainStats,
    /// |H(end) − H(0)|/H(0).
    pub energy_drift: f64,
    /// Total free-flight time (between contact episodes, including the short flights
    /// inside a ringing impact) after collision `skip`.
    pub free_time: f64,
    /// ∫ E_tr/E0 dt over that free-flight time.
    pub free_etr_integral: f64,
    /// Total time inside contact episodes after collision `skip`.
    pub contact_time: f64,
    /// ∫ E_tr/E0 dt over that contact time; the time average of E_tr/E0 over all
    /// time is (free_etr_integral + contact_etr_integral)/(free_time + contact_time).
    pub contact_etr_integral: f64,
}

impl TwoRodRun {
    /// Time average of E_tr/E0 after collision `skip` (free flights and contacts).
    pub fn time_mean_etr(&self) -> f64 {
        (self.free_etr_integral + self.contact_etr_integral) / (self.free_time + self.contact_time)
    }
}

/// Runs `n` collisions of the two-rod experiment; time integrals start after
/// collision `skip`.
///
/// A collision is a maximal run of contact episodes at the same end: with a truncated
/// mode sum the ends ring, so one impact opens and closes the contact several times
/// (measured: 11 episodes in the first impact at M = 8, κ = 1000), while in free
/// flight Ṙ_21 is constant, so a new impact at the same end is impossible before one
/// at the other end.
pub fn run_two_rods(setup: &TwoRodSetup, n: usize, skip: usize) -> Result<TwoRodRun> {
    let clock = Instant::now();
    let mut chain = setup.chain()?;
    let e_start = chain.energy();
    let mut run = TwoRodRun {
        modes: setup.modes,
        skip,
        records: Vec::with_capacity(n),
        wall_seconds: 0.0,
        stats: ChainStats::default(),
        energy_drift: 0.0,
        free_time: 0.0,
        free_etr_integral: 0.0,
        contact_time: 0.0,
        contact_etr_integral: 0.0,
    };
    let mut pending: Option<(TwoRodRecord, f64)> = None;
    let mut last: Option<(f64, f64)> = None;
    while run.records.len() < n {
        let recs = chain.run_collisions(1);
        let Some(c) = recs.last() else {
            return Err(Error::NoFurtherCollision {
                collisions: run.records.len() + usize::from(pending.is_some()),
            });
        };
        let (e_tr, eta, w) = snapshot(&chain, setup);
        // E_tr/E0 = (Ṙ_21/V0)² with V0 = 1.
        let contact_time: f64 = recs.iter().map(|r| r.t_end - r.t_start).sum();
        let contact_int: f64 = recs.iter().map(|r| r.rel_v2_integral).sum();
        let (free_dt, free_int) = match last {
            Some((t_end, e)) => (recs[0].t_start - t_end, e * (recs[0].t_start - t_end)),
            None => (0.0, 0.0),
        };
        if let Some((p, _)) = &mut pending {
            p.span += free_dt;
            p.etr_integral += free_int;
        }
        if run.records.len() >= skip {
            run.free_time += free_dt;
            run.free_etr_integral += free_int;
            run.contact_time += contact_time;
            run.contact_etr_integral += contact_int;
        }
        last = Some((c.t_end, e_tr));
        match &mut pending {
            Some((p, v_pre)) if p.contact == c.contact => {
                p.t_end = c.t_end;
                p.episodes += recs.len();
                p.eps = -c.v_post / *v_pre;
                p.span += contact_time;
                p.etr_integral += contact_int;
                (p.e_tr, p.eta, p.w) = (e_tr, eta, w);
            }
            _ => {
                if let Some((p, _)) = pending.take() {
                    run.records.push(p);
                }
                let r = TwoRodRecord {
                    collision: run.records.len() + 1,
                    contact: c.contact,
                    episodes: recs.len(),
                    t_start: recs[0].t_start,
                    t_end: c.t_end,
                    e_tr,
                    eps: -c.v_post / recs[0].v_pre,
                    eta,
                    w,
                    span: contact_time,
                    etr_integral: contact_int,
                };
                pending = Some((r, recs[0].v_pre));
            }
        }
    }
    run.energy_drift = (chain.energy() - e_start).abs() / e_start;
    run.stats = chain.stats();
    run.wall_seconds = clock.elapsed().as_secs_f64();
    Ok(run)
}

/// First collision after which η − η_eq has fallen below 1/e of its value after the
/// first collision (the modal relaxation time of Fig. 2 of Giese).
pub fn eta_relaxation(records: &[TwoRodRecord], eta_eq: f64) -> Option<usize> {
    let d0 = records.first()?.eta - eta_eq;
    records
        .iter()
        .find(|r| r.eta - eta_eq < d0 / std::f64::consts::E)
        .map(|r| r.collision)
}

/// First collision with η within `fraction` of η_eq (η < (1 + fraction) η_eq).
pub fn eta_within(records: &[TwoRodRecord], eta_eq: f64, fraction: f64) -> Option<usize> {
    records
        .iter()
        .find(|r| r.eta < (1.0 + fraction) * eta_eq)
        .map(|r| r.collision)
}

/// First collision at which the mean E_tr/E0 of the next `window` collisions has fallen
/// below `factor` times the plateau (the cooling time of Fig. 1 of Giese).
pub fn cooling_collision(
    records: &[TwoRodRecord],
    plateau: f64,
    window: usize,
    factor: f64,
) -> Option<usize> {
    let threshold = factor * plateau;
    records
        .windows(window.max(1))
        .find(|w| w.iter().map(|r| r.e_tr).sum::<f64>() < threshold * w.len() as f64)
        .map(|w| w[0].collision)
}

/// The relative modal energies w averaged over `records` (rod 1 ν = 1..M, then rod 2).
pub fn mean_spectrum(records: &[TwoRodRecord]) -> Vec<f64> {
    let Some(first) = records.first() else {
        return Vec::new();
    };
    let mut mean = vec![0.0; first.w.len()];
    for r in records {
        mean.iter_mut()
            .zip(&r.w)
            .for_each(|(m, w)| *m += w / records.len() as f64);
    }
    mean
}
