//! Helpers shared by the gas tests.
#![allow(dead_code)] // each test binary uses a subset

use gas::observe::temperature;
use gas::Engine;
use restitution::{Constant, Restitution, ScaledForm, Viscoelastic};

/// Mean and standard error of the mean of independent values (batch means, seeds).
pub fn mean_and_error(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// ln T at the given times of any engine.
pub fn log_temperatures<const D: usize>(engine: &mut dyn Engine<D>, times: &[f64]) -> Vec<f64> {
    times
        .iter()
        .map(|&t| {
            engine.run_until(t);
            temperature(engine.system()).ln()
        })
        .collect()
}

/// The viscoelastic law with material constant `beta` and scaled form `form`.
pub fn viscoelastic(beta: f64, form: &str) -> Viscoelastic {
    Viscoelastic::new(beta, form.parse::<ScaledForm>().unwrap()).unwrap()
}

/// A constant coefficient of restitution.
pub fn constant(eps: f64) -> Box<dyn Restitution> {
    Box::new(Constant::new(eps).unwrap())
}
