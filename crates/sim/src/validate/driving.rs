//! `[driving]`: white noise or the Gaussian thermostat, for the engines that drive (DSMC
//! blocks at every step, the event-driven engine at discrete times).

use crate::description::{DrivingKind, RunDescription};
use crate::engines::{Abilities, DrivingTimes};
use crate::error::{Error, Result};
use crate::validate::LawSpec;
use gas::driving::{Driving, Thermostat, WhiteNoise};

/// The driving of the run and the event-driven interval between its applications, if
/// given (the default follows from the plan: [`crate::species::default_driving_interval`]).
pub(crate) fn driving_spec(
    description: &RunDescription,
    engine: &Abilities,
    law: &LawSpec,
) -> Result<(Option<Driving>, Option<f64>)> {
    let Some(d) = &description.driving else {
        return Ok((None, None));
    };
    let driving = match d.kind {
        DrivingKind::WhiteNoise => {
            if d.temperature.is_some() {
                return Err(Error::input(
                    "driving.temperature",
                    "only for kind = \"gaussian-thermostat\"",
                ));
            }
            let strength = d
                .strength
                .ok_or_else(|| Error::input("driving.strength", "missing for white noise"))?;
            Driving::WhiteNoise(
                WhiteNoise::new(strength).map_err(|_| {
                    Error::out_of_range("driving.strength", strength, "finite and > 0")
                })?,
            )
        }
        DrivingKind::GaussianThermostat => {
            if d.strength.is_some() {
                return Err(Error::input(
                    "driving.strength",
                    "only for kind = \"white-noise\"",
                ));
            }
            let t = d.temperature.unwrap_or(description.system.temperature);
            Driving::Thermostat(
                Thermostat::new(t)
                    .map_err(|_| Error::out_of_range("driving.temperature", t, "finite and > 0"))?,
            )
        }
    };
    if matches!(law, LawSpec::Stochastic { .. }) {
        return Err(Error::input(
            "driving",
            "a stochastic law's baths exchange energy with the particles; driving is for the \
             other laws",
        ));
    }
    match engine.driving {
        DrivingTimes::AtSteps => {
            if let Some(dt) = d.interval {
                return Err(Error::out_of_range(
                    "driving.interval",
                    dt,
                    "absent with run.engine = \"dsmc\": the DSMC drives at every step (set \
                     run.collisions_per_step or run.time_step)",
                ));
            }
            Ok((Some(driving), None))
        }
        DrivingTimes::AtIntervals => {
            if let Some(dt) = d.interval {
                if !(dt.is_finite() && dt > 0.0) {
                    return Err(Error::out_of_range(
                        "driving.interval",
                        dt,
                        "finite and > 0",
                    ));
                }
            }
            Ok((Some(driving), d.interval))
        }
        DrivingTimes::Never => Err(Error::input(
            "driving",
            "driving runs in run.engine = \"event-driven\" (at discrete times) or \"dsmc\" with \
             dsmc_scheme = \"blocks\" (at its steps)",
        )),
    }
}
