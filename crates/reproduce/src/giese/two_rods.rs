//! The two-rod experiment of Giese's Figs. 1 and 2 for any gamma, kappa and list of mode
//! counts, as `haff rods two-rods` writes it ([`run`]), and the curves that it and
//! `giese-fig1`, `giese-fig2` draw alike: E_tr after each collision and its running mean,
//! the spectral entropy, the equilibrium levels and the mean spectrum of each rod.

use super::level;
use rods::chain::{
    equipartition_mode_share, run_two_rods, running_mean_e_tr, TwoRodRecord, TwoRodSetup,
    TwoRodSummary, RUNNING_WINDOW,
};
use sim::output::{number, write_csv_file, write_json_file};
use sim::plot::Figure;
use std::fmt;
use std::path::{Path, PathBuf};

/// The settings of [`run`]; the command checks them against `rods::ranges`
/// (`TWO_RODS_GAMMA`, `TWO_RODS_KAPPA`, `MODES`, `C_H`).
#[derive(Debug, Clone, PartialEq)]
pub struct TwoRodsSettings {
    /// Length ratio gamma = l1/l2.
    pub gamma: f64,
    /// kappa = alpha l V0 / c.
    pub kappa: f64,
    /// Modes per rod: one experiment per value, in this order.
    pub modes: Vec<usize>,
    /// Collisions per experiment.
    pub collisions: usize,
    /// Collisions before the means (spectrum, plateau) start.
    pub transient: usize,
    /// Step constant of the contact integrator.
    pub c_h: f64,
    /// The directory (existing) of two_rods.csv, spectrum.csv, summary.json, energy.png,
    /// entropy.png and spectrum.png.
    pub out: PathBuf,
}

/// Why [`run`] failed.
#[derive(Debug)]
pub enum TwoRodsError {
    /// An experiment of the rods library failed (its settings, or the run itself); nothing
    /// has been written.
    Run(rods::Error),
    /// An output file could not be written.
    Output(sim::Error),
}

impl fmt::Display for TwoRodsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TwoRodsError::Run(e) => e.fmt(f),
            TwoRodsError::Output(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for TwoRodsError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TwoRodsError::Run(e) => Some(e),
            TwoRodsError::Output(e) => Some(e),
        }
    }
}

impl From<sim::Error> for TwoRodsError {
    fn from(e: sim::Error) -> Self {
        TwoRodsError::Output(e)
    }
}

/// One two-rod experiment per entry of `settings.modes` (two cold rods on a ring, E_tr,
/// eps and the spectral entropy after every collision), then, in `settings.out`:
/// two_rods.csv (modes, collision, e_tr, eps, eta), spectrum.csv (the mean modal spectrum
/// of every experiment: modes, rod, mode, w), summary.json (the summaries), energy.png
/// (E_tr, its running mean and E0/(2M+1)), entropy.png (eta and eta_eq) and spectrum.png
/// (the mean spectrum of the last experiment, Fig. 1's inset). Returns the summaries, in
/// the order of `settings.modes`.
pub fn run(settings: &TwoRodsSettings) -> Result<Vec<TwoRodSummary>, TwoRodsError> {
    run_reporting(settings, &mut |_| {})
}

/// [`run`], calling `done` with the number of experiments finished after each (a progress
/// bar).
pub fn run_reporting(
    settings: &TwoRodsSettings,
    done: &mut dyn FnMut(usize),
) -> Result<Vec<TwoRodSummary>, TwoRodsError> {
    let TwoRodsSettings {
        gamma,
        kappa,
        collisions,
        transient,
        c_h,
        ..
    } = *settings;
    let mut rows = Vec::new();
    let mut spectra = Vec::new();
    let mut summaries = Vec::new();
    let mut last_spectrum = Vec::new();
    let title = format!("two rods, gamma = {gamma}, kappa = {kappa}: E_tr/E0 after each collision");
    // Per-collision values thin, their running means and the equilibria on top.
    let mut energy = Figure::new(title, "collision", "E_tr / E0").log(true, true);
    let title = format!("two rods, gamma = {gamma}, kappa = {kappa}: spectral entropy");
    let mut entropy = Figure::new(title, "collision", "eta = 1 - h / ln(2M)").log(true, false);
    for &m in &settings.modes {
        let setup = TwoRodSetup {
            gamma,
            kappa,
            modes: m,
            gap: 1.0,
            c_h,
        };
        let run = run_two_rods(&setup, collisions, transient).map_err(TwoRodsError::Run)?;
        let summary = run.summary();
        let (eq, plateau) = (summary.eta_equilibrium, summary.equipartition_per_collision);
        summaries.push(summary);
        done(summaries.len());
        for r in &run.records {
            rows.push(vec![
                m.to_string(),
                r.collision.to_string(),
                number(r.e_tr),
                number(r.eps),
                number(r.eta),
            ]);
        }
        last_spectrum = run.mean_spectrum();
        for (rod, mode, w) in spectrum_entries(&last_spectrum, m) {
            spectra.push(vec![
                m.to_string(),
                rod.to_string(),
                mode.to_string(),
                number(w),
            ]);
        }
        let (window, running) = running_mean(&run.records);
        energy = energy
            .noisy(format!("M = {m}"), e_tr_curve(&run.records))
            .theory(
                format!("equilibrium 1/(2M+1), M = {m}"),
                over_collisions(plateau, collisions),
            )
            .line(
                format!("M = {m}, mean of {window} collisions"),
                running_curve(&running),
            );
        entropy = entropy
            .line(format!("M = {m}"), eta_curve(&run.records, 1.0))
            .theory(
                format!("equilibrium eta_eq, M = {m}"),
                over_collisions(eq, collisions),
            );
    }
    let file = |name: &str| settings.out.join(name);
    write_csv_file(
        &file("two_rods.csv"),
        &["modes", "collision", "e_tr", "eps", "eta"],
        rows,
    )?;
    write_csv_file(
        &file("spectrum.csv"),
        &["modes", "rod", "mode", "w"],
        spectra,
    )?;
    write_json_file(&file("summary.json"), &summaries)?;
    energy.write_png(&file("energy.png"))?;
    entropy.write_png(&file("entropy.png"))?;
    if let Some(last) = summaries.last() {
        plot_spectrum(&file("spectrum.png"), last, &last_spectrum)?;
    }
    Ok(summaries)
}

/// The mean modal spectrum `w` (rod 1 modes 1..M, then rod 2) of the run summarized by
/// `last` as w(mode) per rod (inset of Fig. 1).
fn plot_spectrum(path: &Path, last: &TwoRodSummary, spectrum: &[f64]) -> sim::Result<()> {
    let modes = last.modes;
    let title = format!(
        "mean modal energies w after collision {} (M = {modes})",
        last.transient
    );
    Figure::new(title, "mode nu", "<w>")
        .line("rod 1", rod_spectrum(spectrum, modes, 0))
        .line("rod 2", rod_spectrum(spectrum, modes, 1))
        .theory(
            "equilibrium 1/(2M)",
            over_modes(equipartition_mode_share(modes), modes),
        )
        .write_png(path)
}

// ---------------------------------------------------------------------------------------
// The curves of the two-rod experiment, as `run`, `giese-fig1` and `giese-fig2` draw them.

/// E_tr/E0 after each collision: (collision, E_tr/E0).
pub(super) fn e_tr_curve(records: &[TwoRodRecord]) -> Vec<(f64, f64)> {
    records
        .iter()
        .map(|r| (r.collision as f64, r.e_tr))
        .collect()
}

/// The running mean of E_tr/E0 over [`RUNNING_WINDOW`] collisions (all of them if there
/// are fewer): the window and (collision in the middle of the window, mean).
pub(super) fn running_mean(records: &[TwoRodRecord]) -> (usize, Vec<(usize, f64)>) {
    let window = RUNNING_WINDOW.min(records.len());
    (window, running_mean_e_tr(records, window))
}

/// The running mean of [`running_mean`] as a curve.
pub(super) fn running_curve(running: &[(usize, f64)]) -> Vec<(f64, f64)> {
    running.iter().map(|&(k, e)| (k as f64, e)).collect()
}

/// The spectral entropy eta = 1 - h/ln(2M) after each collision in units of `unit` (1: eta
/// itself; eta_eq: relative to its equilibrium): (collision, eta / unit).
pub(super) fn eta_curve(records: &[TwoRodRecord], unit: f64) -> Vec<(f64, f64)> {
    records
        .iter()
        .map(|r| (r.collision as f64, r.eta / unit))
        .collect()
}

/// An equilibrium level `y` over collisions 1..`collisions`.
pub(super) fn over_collisions(y: f64, collisions: usize) -> Vec<(f64, f64)> {
    level(y, 1.0, collisions as f64)
}

/// A level `y` over the modes 1..`modes` of one rod (equipartition of the spectrum).
pub(super) fn over_modes(y: f64, modes: usize) -> Vec<(f64, f64)> {
    level(y, 1.0, modes as f64)
}

/// The mean modal energies of rod `rod` (0: rod 1, 1: rod 2) of a spectrum with `modes`
/// modes per rod (rod 1 first): (mode nu = 1..M, <w>).
pub(super) fn rod_spectrum(spectrum: &[f64], modes: usize, rod: usize) -> Vec<(f64, f64)> {
    spectrum
        .iter()
        .skip(rod * modes)
        .take(modes)
        .enumerate()
        .map(|(j, w)| ((j + 1) as f64, *w))
        .collect()
}

/// Every entry of a spectrum with `modes` modes per rod as (rod 1 or 2, mode 1..M, w).
pub(super) fn spectrum_entries(
    spectrum: &[f64],
    modes: usize,
) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
    spectrum
        .iter()
        .enumerate()
        .map(move |(j, w)| (j / modes + 1, j % modes + 1, *w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spectrum_splits_into_rods() {
        let spectrum = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
        assert_eq!(
            rod_spectrum(&spectrum, 3, 1),
            vec![(1.0, 0.4), (2.0, 0.5), (3.0, 0.6)]
        );
        let entries: Vec<_> = spectrum_entries(&spectrum, 3).collect();
        assert_eq!(entries[0], (1, 1, 0.1));
        assert_eq!(entries[4], (2, 2, 0.5));
    }

    /// `run` writes its six files and returns one summary per entry of `modes`.
    #[test]
    fn run_writes_its_files() {
        let out = std::env::temp_dir().join(format!("haff-two-rods-{}", std::process::id()));
        std::fs::create_dir_all(&out).unwrap();
        let settings = TwoRodsSettings {
            gamma: 0.6173,
            kappa: 100.0,
            modes: vec![2, 3],
            collisions: 20,
            transient: 5,
            c_h: 0.125,
            out: out.clone(),
        };
        let summaries = run(&settings).unwrap();
        assert_eq!(
            summaries.iter().map(|s| s.modes).collect::<Vec<_>>(),
            [2, 3]
        );
        for name in [
            "two_rods.csv",
            "spectrum.csv",
            "summary.json",
            "energy.png",
            "entropy.png",
            "spectrum.png",
        ] {
            assert!(out.join(name).is_file(), "{name}");
        }
        let spectrum = std::fs::read_to_string(out.join("spectrum.csv")).unwrap();
        assert_eq!(spectrum.lines().count(), 1 + 2 * 2 + 2 * 3);
        std::fs::remove_dir_all(&out).unwrap();
    }
}
