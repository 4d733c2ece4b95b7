//! The outcome of a two-rod experiment (Figs. 1 and 2 of Giese) against equipartition.
//!
//! After the transient the two rods share the energy E0 microcanonically among 4M + 1
//! quadratic terms: the relative translation (one term, momentum being conserved) and
//! 2M modes with two terms each. The fraction x = E_tr/E0 is then Beta(1/2, 2M)
//! distributed, so its time average is 1/(4M + 1) ([`equipartition_time`]). Collisions
//! sample x at a rate proportional to the relative speed, ∝ √x: the mean of E_tr/E0 per
//! collision is ⟨x^{3/2}⟩/⟨x^{1/2}⟩ = B(2, 2M)/B(1, 2M) = 1/(2M + 1)
//! ([`equipartition_per_collision`], Giese's E0/(2M + 1)).

use super::two_rods::{
    cooling_collision, eta_equilibrium, eta_relaxation, eta_within, mean_spectrum, TwoRodRecord,
    TwoRodRun,
};
use serde::{Deserialize, Serialize};

/// Collisions per window of the running mean of E_tr/E0 (the cooling time of
/// [`TwoRodSummary::cooling_collision`] and [`running_mean_e_tr`]).
pub const RUNNING_WINDOW: usize = 25;

/// Cooling: the running mean has fallen below this factor times the plateau.
const COOLING_FACTOR: f64 = 2.0;

/// η counts as relaxed within this fraction of η_eq.
const ETA_FRACTION: f64 = 0.2;

/// Mean E_tr/E0 per collision at equipartition: 1/(2M + 1) (see the module documentation).
pub fn equipartition_per_collision(modes: usize) -> f64 {
    1.0 / (2.0 * modes as f64 + 1.0)
}

/// Mean relative energy w of one of the 2M modes of the two rods at equipartition, 1/(2M).
pub fn equipartition_mode_share(modes: usize) -> f64 {
    0.5 / modes as f64
}

/// Time average of E_tr/E0 at equipartition: 1/(4M + 1) (see the module documentation).
pub fn equipartition_time(modes: usize) -> f64 {
    1.0 / (4.0 * modes as f64 + 1.0)
}

/// Running mean of E_tr/E0 over `window` consecutive collisions (reduced to the number of
/// records if there are fewer), as (collision in the middle of the window, mean).
pub fn running_mean_e_tr(records: &[TwoRodRecord], window: usize) -> Vec<(usize, f64)> {
    let window = window.min(records.len()).max(1);
    records
        .windows(window)
        .map(|w| {
            let mean = w.iter().map(|r| r.e_tr).sum::<f64>() / window as f64;
            (w[window / 2].collision, mean)
        })
        .collect()
}

/// One two-rod experiment's outcome: means after the transient against equipartition,
/// and the relaxation times of η and of E_tr.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TwoRodSummary {
    /// Modes per rod M.
    pub modes: usize,
    /// Collisions recorded.
    pub collisions: usize,
    /// Collisions before the means start.
    pub transient: usize,
    /// Wall-clock seconds of the run.
    pub wall_seconds: f64,
    /// |H(end) − H(0)|/H(0).
    pub energy_drift: f64,
    /// Mean E_tr/E0 per collision after the transient, and Giese's 1/(2M+1).
    pub mean_e_tr: f64,
    pub equipartition_per_collision: f64,
    /// Time average of E_tr/E0 after the transient, and 1/(4M+1).
    pub time_mean_e_tr: f64,
    pub equipartition_time: f64,
    /// Mean spectral entropy η after the transient, and its equilibrium value.
    pub mean_eta: f64,
    pub eta_equilibrium: f64,
    /// [`eta_relaxation`]: η − η_eq below 1/e of its value after the first collision.
    pub eta_relaxation_collision: Option<usize>,
    /// [`eta_within`]: η within 20 % of η_eq.
    pub eta_within_20_percent_collision: Option<usize>,
    /// [`cooling_collision`]: the mean E_tr/E0 of the next 25 collisions below twice
    /// `mean_e_tr`.
    pub cooling_collision: Option<usize>,
}

impl TwoRodRun {
    /// The records after the transient ([`TwoRodRun::skip`]).
    pub fn after_transient(&self) -> &[TwoRodRecord] {
        &self.records[self.skip.min(self.records.len())..]
    }

    /// The relative modal energies w averaged after the transient (rod 1 ν = 1..M, then
    /// rod 2): the inset of Fig. 1 of Giese.
    pub fn mean_spectrum(&self) -> Vec<f64> {
        mean_spectrum(self.after_transient())
    }

    /// The summary of this run (means over the collisions after the transient; NaN if
    /// there are none).
    pub fn summary(&self) -> TwoRodSummary {
        let tail = self.after_transient();
        let mean =
            |f: fn(&TwoRodRecord) -> f64| tail.iter().map(f).sum::<f64>() / tail.len() as f64;
        let m = self.modes;
        let (mean_e_tr, eq) = (mean(|r| r.e_tr), eta_equilibrium(m));
        TwoRodSummary {
            modes: m,
            collisions: self.records.len(),
            transient: self.skip,
            wall_seconds: self.wall_seconds,
            energy_drift: self.energy_drift,
            mean_e_tr,
            equipartition_per_collision: equipartition_per_collision(m),
            time_mean_e_tr: self.time_mean_etr(),
            equipartition_time: equipartition_time(m),
            mean_eta: mean(|r| r.eta),
            eta_equilibrium: eq,
            eta_relaxation_collision: eta_relaxation(&self.records, eq),
            eta_within_20_percent_collision: eta_within(&self.records, eq, ETA_FRACTION),
            cooling_collision: cooling_collision(
                &self.records,
                mean_e_tr,
                RUNNING_WINDOW,
                COOLING_FACTOR,
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::ChainStats;

    fn record(collision: usize, e_tr: f64, eta: f64) -> TwoRodRecord {
        TwoRodRecord {
            collision,
            contact: collision % 2,
            episodes: 1,
            t_start: collision as f64,
            t_end: collision as f64 + 0.5,
            e_tr,
            eps: 1.0,
            eta,
            w: vec![0.25; 4],
            span: 1.0,
            etr_integral: e_tr,
        }
    }

    #[test]
    fn equipartition_by_hand() {
        // M = 1: 5 quadratic terms; per collision 1/3
        assert_eq!(equipartition_time(1), 0.2);
        assert_eq!(equipartition_per_collision(1), 1.0 / 3.0);
        assert_eq!(equipartition_per_collision(4), 1.0 / 9.0);
        assert_eq!(equipartition_time(4), 1.0 / 17.0);
    }

    #[test]
    fn equipartition_per_collision_is_the_flux_weighted_mean() {
        // x ~ Beta(1/2, 2M) on a fine grid: <x^{3/2}>/<x^{1/2}> = 1/(2M+1),
        // <x> = 1/(4M+1).
        let m = 3;
        let b = 2.0 * m as f64;
        let n = 1_000_000;
        // substitution x = s²: the density ∝ x^{−1/2}(1−x)^{b−1} dx becomes ∝ (1−s²)^{b−1} ds
        let (mut w0, mut w_half, mut w1, mut w3) = (0.0, 0.0, 0.0, 0.0);
        for k in 0..n {
            let s = (k as f64 + 0.5) / n as f64;
            let d = (1.0 - s * s).powf(b - 1.0);
            w0 += d;
            w_half += d * s;
            w1 += d * s * s;
            w3 += d * s * s * s;
        }
        let (s1, s3, s_half) = (w1 / w0, w3 / w0, w_half / w0);
        assert!((s1 - equipartition_time(m)).abs() < 1e-9, "{s1}");
        let per_collision = s3 / s_half;
        assert!(
            (per_collision - equipartition_per_collision(m)).abs() < 1e-9,
            "{per_collision}"
        );
    }

    #[test]
    fn summary_and_running_mean_of_constructed_records() {
        let records: Vec<TwoRodRecord> = (1..=40)
            .map(|k| {
                let e = if k <= 10 { 1.0 } else { 0.1 };
                record(k, e, 1.0 / k as f64)
            })
            .collect();
        let run = TwoRodRun {
            modes: 2,
            skip: 10,
            records,
            wall_seconds: 1.5,
            stats: ChainStats::default(),
            energy_drift: 1e-12,
            free_time: 1.0,
            free_etr_integral: 0.2,
            contact_time: 1.0,
            contact_etr_integral: 0.0,
        };
        let s = run.summary();
        assert_eq!((s.modes, s.collisions, s.transient), (2, 40, 10));
        assert!((s.mean_e_tr - 0.1).abs() < 1e-15);
        assert_eq!(s.time_mean_e_tr, 0.1);
        assert_eq!(s.equipartition_per_collision, 0.2);
        assert_eq!(s.equipartition_time, 1.0 / 9.0);
        assert_eq!(s.eta_equilibrium, eta_equilibrium(2));
        // first window of 25 whose mean is below 0.2: collisions 10..34 hold one 1.0
        // (mean 0.136), 9..33 two (0.172), 8..32 three (0.208)
        assert_eq!(s.cooling_collision, Some(9));
        let spectrum = run.mean_spectrum();
        assert_eq!(spectrum.len(), 4);
        assert!(
            spectrum.iter().all(|w| (w - 0.25).abs() < 1e-15),
            "{spectrum:?}"
        );
        let running = running_mean_e_tr(&run.records, RUNNING_WINDOW);
        assert_eq!(running.len(), 16);
        assert_eq!(running[0].0, 13);
        assert!((running[0].1 - (10.0 + 1.5) / 25.0).abs() < 1e-15);
        assert_eq!(running_mean_e_tr(&run.records[..3], 25).len(), 1);
        assert!(running_mean_e_tr(&[], 25).is_empty());
        let json = serde_json::to_value(&s).unwrap();
        for key in [
            "modes",
            "collisions",
            "transient",
            "wall_seconds",
            "energy_drift",
            "mean_e_tr",
            "equipartition_per_collision",
            "time_mean_e_tr",
            "equipartition_time",
            "mean_eta",
            "eta_equilibrium",
            "eta_relaxation_collision",
            "eta_within_20_percent_collision",
            "cooling_collision",
        ] {
            assert!(json.get(key).is_some(), "{key}");
        }
    }
}
