//! The engines `haff run` drives, behind one interface: the sampling loop, outputs,
//! progress bar and check-points are shared; only construction, advancing and the
//! check-point state differ.

use gas::dsmc::{self, HomogeneousSnapshot, Scheme, SpatialOptions, SpatialSnapshot};
use gas::{EventDriven, HomogeneousDsmc, SpatialDsmc, System};
use restitution::Restitution;
use serde::{Deserialize, Serialize};

/// An engine of any kind.
pub enum Engine<const D: usize> {
    EventDriven(Box<EventDriven<D>>),
    Homogeneous(Box<HomogeneousDsmc<D>>),
    Spatial(Box<SpatialDsmc<D>>),
}

/// Counters common to all engines.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Counters {
    pub collisions: u64,
    /// Events (eMD: collisions, cell crossings, stale predictions; DSMC: candidates).
    pub events: u64,
    pub energy_lost: f64,
    /// Sum of impulse times contact distance over collisions, in simulated particles.
    pub virial: f64,
    /// Collisions the TC model made elastic (eMD).
    pub tc_elastic: u64,
}

/// The state of a DSMC engine beyond its particles (for check-points).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct DsmcState {
    pub steps: u64,
    pub draws: u64,
    pub speed_bound: f64,
    pub reference_velocity: Vec<f64>,
    pub temperature: f64,
}

/// How a DSMC engine was set up (from the run file).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DsmcSetup {
    Homogeneous(Scheme),
    Spatial(SpatialOptions),
}

/// Everything a check-point holds about the engine, besides the run file.
pub struct EngineState<const D: usize> {
    pub time: f64,
    pub system: System<D>,
    pub counts: Vec<u64>,
    pub counters: Counters,
    pub tc_last: Option<Vec<f64>>,
    pub dsmc: Option<DsmcState>,
}

impl<const D: usize> Engine<D> {
    /// A DSMC engine at time 0.
    pub fn dsmc(
        system: System<D>,
        phi: f64,
        law: Box<dyn Restitution>,
        seed: u64,
        setup: DsmcSetup,
    ) -> Result<Self, String> {
        Ok(match setup {
            DsmcSetup::Homogeneous(scheme) => Engine::Homogeneous(Box::new(HomogeneousDsmc::new(
                system, phi, law, seed, scheme,
            )?)),
            DsmcSetup::Spatial(options) => {
                Engine::Spatial(Box::new(SpatialDsmc::new(system, phi, law, seed, options)?))
            }
        })
    }

    /// A DSMC engine continuing from a check-point state.
    pub fn restore_dsmc(
        state: EngineState<D>,
        phi: f64,
        law: Box<dyn Restitution>,
        seed: u64,
        setup: DsmcSetup,
    ) -> Result<Self, String> {
        let extra = state
            .dsmc
            .ok_or("the check-point holds no DSMC state (was it an event-driven run?)")?;
        let reference_velocity: [f64; D] = extra
            .reference_velocity
            .as_slice()
            .try_into()
            .map_err(|_| "check-point of another dimension".to_string())?;
        let tally = dsmc::Tally {
            collisions: state.counters.collisions,
            candidates: state.counters.events,
            energy_lost: state.counters.energy_lost,
            virial: state.counters.virial,
        };
        macro_rules! snapshot {
            ($options:expr) => {
                dsmc::Snapshot {
                    system: state.system,
                    packing_fraction: phi,
                    seed,
                    options: $options,
                    time: state.time,
                    steps: extra.steps,
                    tally,
                    reference_velocity,
                    speed_bound: extra.speed_bound,
                    draws: extra.draws,
                    temperature: extra.temperature,
                }
            };
        }
        Ok(match setup {
            DsmcSetup::Homogeneous(scheme) => {
                let snapshot: HomogeneousSnapshot<D> = snapshot!(scheme);
                Engine::Homogeneous(Box::new(HomogeneousDsmc::restore(snapshot, law)?))
            }
            DsmcSetup::Spatial(options) => {
                let snapshot: SpatialSnapshot<D> = snapshot!(options);
                Engine::Spatial(Box::new(SpatialDsmc::restore(snapshot, law)?))
            }
        })
    }

    pub fn run_collisions(&mut self, collisions: u64) {
        match self {
            Engine::EventDriven(e) => e.run_collisions(collisions),
            Engine::Homogeneous(e) => e.run_collisions(collisions),
            Engine::Spatial(e) => e.run_collisions(collisions),
        }
    }

    pub fn run_until(&mut self, t: f64) {
        match self {
            Engine::EventDriven(e) => e.run_until(t),
            Engine::Homogeneous(e) => e.run_until(t),
            Engine::Spatial(e) => e.run_until(t),
        }
    }

    pub fn time(&self) -> f64 {
        match self {
            Engine::EventDriven(e) => e.time(),
            Engine::Homogeneous(e) => e.time(),
            Engine::Spatial(e) => e.time(),
        }
    }

    pub fn collisions_per_particle(&self) -> f64 {
        match self {
            Engine::EventDriven(e) => e.collisions_per_particle(),
            Engine::Homogeneous(e) => e.collisions_per_particle(),
            Engine::Spatial(e) => e.collisions_per_particle(),
        }
    }

    pub fn counters(&self) -> Counters {
        match self {
            Engine::EventDriven(e) => {
                let t = e.tally();
                Counters {
                    collisions: t.collisions,
                    events: t.events,
                    energy_lost: t.energy_lost,
                    virial: t.virial,
                    tc_elastic: t.tc_elastic,
                }
            }
            Engine::Homogeneous(e) => dsmc_counters(e.tally()),
            Engine::Spatial(e) => dsmc_counters(e.tally()),
        }
    }

    /// Physical particles each simulated particle stands for (spatial DSMC may
    /// under-resolve; 1 otherwise): the collisional pressure scales with it.
    pub fn weight(&self) -> f64 {
        match self {
            Engine::Spatial(e) => e.weight(),
            _ => 1.0,
        }
    }

    /// The baths of a stochastic law (event-driven engine only).
    pub fn bath_state(&self) -> Option<gas::BathState> {
        match self {
            Engine::EventDriven(e) => e.bath_state(),
            _ => None,
        }
    }

    /// The time of inelastic collapse if the event-driven engine stopped there.
    pub fn collapsed(&self) -> Option<f64> {
        match self {
            Engine::EventDriven(e) => e.collapsed(),
            _ => None,
        }
    }

    pub fn system(&mut self) -> &System<D> {
        match self {
            Engine::EventDriven(e) => e.system(),
            Engine::Homogeneous(e) => e.system(),
            Engine::Spatial(e) => e.system(),
        }
    }

    /// The state to continue from bit for bit (the event-driven engine is synchronized
    /// first: all particles at the same time, every event predicted afresh).
    pub fn state(&mut self) -> EngineState<D> {
        let counters = self.counters();
        match self {
            Engine::EventDriven(e) => {
                e.synchronize();
                let tc_last = e.tc_model().map(|(_, last)| last.to_vec());
                let counts = e.counts().to_vec();
                EngineState {
                    time: e.time(),
                    system: e.system().clone(),
                    counts,
                    counters,
                    tc_last,
                    dsmc: None,
                }
            }
            Engine::Homogeneous(e) => dsmc_state(e.snapshot(), counters),
            Engine::Spatial(e) => dsmc_state(e.snapshot(), counters),
        }
    }
}

fn dsmc_counters(t: dsmc::Tally) -> Counters {
    Counters {
        collisions: t.collisions,
        events: t.candidates,
        energy_lost: t.energy_lost,
        virial: t.virial,
        tc_elastic: 0,
    }
}

fn dsmc_state<const D: usize, O>(s: dsmc::Snapshot<D, O>, counters: Counters) -> EngineState<D> {
    EngineState {
        time: s.time,
        system: s.system,
        counts: Vec::new(),
        counters,
        tc_last: None,
        dsmc: Some(DsmcState {
            steps: s.steps,
            draws: s.draws,
            speed_bound: s.speed_bound,
            reference_velocity: s.reference_velocity.to_vec(),
            temperature: s.temperature,
        }),
    }
}
