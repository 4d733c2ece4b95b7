//! An observer for studies set up in code (the reproduced papers, the benches): a value
//! measured on the engine at every sample of a schedule, kept in memory (and in
//! check-points), no file. [`sample`] runs an engine through the driver and returns the
//! values.

use crate::driver::{Driven, Driver, Until};
use crate::error::Result;
use crate::observer::{record_of, records_from, Observer};
use crate::schedule::{Schedule, Target};
use gas::Engine;
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// What a [`Probe`] measures.
pub type Measurement<const D: usize, T> = Box<dyn FnMut(&mut dyn Engine<D>) -> T + Send>;

/// The value `measure` gives at every sample.
pub struct Probe<const D: usize, T> {
    name: &'static str,
    measure: Measurement<D, T>,
    pub values: Vec<T>,
}

impl<const D: usize, T> Probe<D, T> {
    /// A probe whose records are called `name` in check-points.
    pub fn new(name: &'static str, measure: Measurement<D, T>) -> Self {
        Probe {
            name,
            measure,
            values: Vec::new(),
        }
    }
}

impl<const D: usize, T> Observer<D> for Probe<D, T>
where
    T: Serialize + DeserializeOwned + Send + 'static,
{
    fn name(&self) -> &'static str {
        self.name
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if target.sample.is_some() {
            self.values.push((self.measure)(engine));
        }
        Ok(())
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(&self.values)
    }

    /// One value per sample done.
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        _engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let values: Vec<T> = records_from(record)?;
        if values.len() != schedule.samples_before(done) {
            return Err("one value per sample done".into());
        }
        self.values = values;
        Ok(())
    }

    /// The values stay in memory: the study that set the probe writes them.
    fn write(&self, _dir: &Path) -> Result<()> {
        Ok(())
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// Runs `engine` through the driver to the end of `schedule` and returns what `measure`
/// gave at each sample.
pub fn sample<const D: usize, T>(
    engine: Box<dyn Driven<D>>,
    schedule: Schedule,
    measure: impl FnMut(&mut dyn Engine<D>) -> T + Send + 'static,
) -> Result<Vec<T>>
where
    T: Serialize + DeserializeOwned + Clone + Send + 'static,
{
    let probe = Probe::<D, T>::new("probe", Box::new(measure));
    let mut driver = Driver::new(engine, vec![Box::new(probe)], schedule);
    driver.go(&mut (), Until::default(), None)?;
    let mut values = Vec::new();
    if let Some(probe) = driver.observer::<Probe<D, T>>() {
        values.clone_from(&probe.values);
    }
    Ok(values)
}
