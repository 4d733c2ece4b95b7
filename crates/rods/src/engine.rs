//! The rod chain behind the engine interface of `gas` ([`gas::Engine`], [`gas::Checkpoint`]):
//! what applies to a Hamiltonian chain. A collision is an impact (counted from contact
//! episodes by [`Impacts`]); events are contact episodes; no energy is dissipated (the
//! translational energy an impact loses goes into the modes: see [`Chain::energy`] and
//! [`Chain::modal_energies`]), so `energy_lost` and the virial stay 0. The state seen by
//! observers is the rods as hard rods: centres in [0, P), centre-of-mass velocities,
//! radius l/2, mass rho l.

use crate::chain::{Chain, CollisionRecord, Impacts};
use gas::engine::{Report, ReportSection, ReportValue};
use gas::{Checkpoint, Counters, Engine, System};
use serde::{Deserialize, Serialize};

/// A rod chain with its impact counter.
#[derive(Debug, Clone)]
pub struct ChainEngine {
    chain: Chain,
    impacts: Impacts,
    episodes: u64,
    /// Episodes completed on the way to the end of a run in time that has paused, not yet
    /// counted: [`Impacts::count`] orders the episodes of one call by their start, so a run
    /// toward a time counts them together when it gets there, however it was paused.
    pending: Vec<CollisionRecord>,
    system: System<1>,
}

/// The complete state of a [`ChainEngine`] (the chain serializes completely).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainEngineState {
    pub chain: Chain,
    pub impacts: Impacts,
    pub episodes: u64,
    pub pending: Vec<CollisionRecord>,
}

impl ChainEngine {
    /// The engine of `chain`, no impacts counted yet.
    pub fn new(chain: Chain) -> Self {
        let rods = chain.n_rods();
        ChainEngine {
            chain,
            impacts: Impacts::new(rods),
            episodes: 0,
            pending: Vec::new(),
            system: System {
                sides: [0.0],
                positions: Vec::new(),
                velocities: Vec::new(),
                radii: Vec::new(),
                masses: Vec::new(),
            },
        }
    }

    /// The engine saved as `state`; fails if the impact counter is not of this chain.
    pub fn from_state(state: ChainEngineState) -> gas::Result<Self> {
        let rods = state.chain.n_rods();
        if state.impacts.rods() != rods {
            return Err(gas::Error::LengthMismatch {
                what: format!(
                    "the impact counter ({} rods) and the chain ({rods} rods)",
                    state.impacts.rods()
                ),
            });
        }
        let mut engine = ChainEngine::new(state.chain);
        engine.impacts = state.impacts;
        engine.episodes = state.episodes;
        engine.pending = state.pending;
        Ok(engine)
    }

    /// The chain (for modal energies, the total energy, ...).
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// Impacts counted so far.
    pub fn impacts(&self) -> &Impacts {
        &self.impacts
    }

    fn count(&mut self, records: &[crate::chain::CollisionRecord]) {
        self.impacts.count(records);
        self.episodes += records.len() as u64;
    }
}

impl Engine<1> for ChainEngine {
    fn run_until(&mut self, t: f64) {
        let mut records = std::mem::take(&mut self.pending);
        records.extend(self.chain.run_until(t));
        self.count(&records);
    }

    /// Runs contact episodes until `collisions` more impacts have been counted.
    fn run_collisions(&mut self, collisions: u64) {
        let pending = std::mem::take(&mut self.pending);
        self.count(&pending);
        let target = self.impacts.collisions() + collisions;
        while self.impacts.collisions() < target {
            let records = self.chain.run_collisions(1);
            if records.is_empty() {
                break;
            }
            self.count(&records);
        }
    }

    /// Runs toward `end` contact episode by contact episode, pausing after about
    /// `pause` minus the impacts counted so far more episodes (or at `collisions`); a run
    /// toward a finite `end` counts its episodes when it gets there, together, as
    /// [`Engine::run_until`] does (see [`ChainEngine::pending`]): the pieces compose to one
    /// call, integration and count alike ([`Chain::run_bounded`]).
    fn run_paused(&mut self, end: f64, collisions: u64, pause: u64) {
        if !end.is_finite() {
            let have = self.impacts.collisions();
            self.run_collisions(collisions.min(pause).saturating_sub(have));
            return;
        }
        let budget = collisions
            .min(pause)
            .saturating_sub(self.impacts.collisions());
        let mut episodes = 0;
        while episodes < budget.max(1) {
            let records = self.chain.run_bounded(end, 1);
            if records.is_empty() {
                // Nothing left before `end`: the time reaches it, the episodes are counted.
                self.run_until(end);
                return;
            }
            episodes += records.len() as u64;
            self.pending.extend(records);
        }
    }

    fn time(&self) -> f64 {
        self.chain.time()
    }

    /// The section `chain`: `mode_energy`, the energy of all rods' internal modes, and
    /// `total_energy`, the chain's energy ([`Chain::energy`]).
    fn report(&self) -> Report {
        let chain = &self.chain;
        let modes: f64 = (0..chain.n_rods())
            .map(|i| chain.modal_energies(i).iter().sum::<f64>())
            .sum();
        Report {
            sections: vec![ReportSection {
                name: "chain",
                values: vec![
                    ("mode_energy", ReportValue::Real(modes)),
                    ("total_energy", ReportValue::Real(chain.energy())),
                ],
            }],
        }
    }

    fn counters(&self) -> Counters {
        Counters {
            collisions: self.impacts.collisions(),
            events: self.episodes + self.pending.len() as u64,
            ..Counters::default()
        }
    }

    fn particles(&self) -> usize {
        self.chain.n_rods()
    }

    fn system(&mut self) -> &System<1> {
        let perimeter = self.chain.perimeter();
        let s = &mut self.system;
        s.sides = [perimeter];
        s.positions = self
            .chain
            .positions()
            .into_iter()
            .map(|x| [gas::system::wrap(x, perimeter)])
            .collect();
        s.velocities = self.chain.velocities().into_iter().map(|v| [v]).collect();
        s.radii = self.chain.lengths().into_iter().map(|l| 0.5 * l).collect();
        s.masses = self.chain.masses();
        &self.system
    }

    /// The chain's own record only (its per-rod mode arrays are not counted).
    fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Chain>()
    }
}

impl Checkpoint<1> for ChainEngine {
    type State = ChainEngineState;
    /// The chain's dynamics is all in its state: a restore needs nothing else.
    type Needs = ();

    fn save(&mut self) -> ChainEngineState {
        ChainEngineState {
            chain: self.chain.clone(),
            impacts: self.impacts.clone(),
            episodes: self.episodes,
            pending: self.pending.clone(),
        }
    }

    /// Restores the chain after checking it ([`ChainEngine::from_state`]).
    fn restore(state: ChainEngineState, _needs: ()) -> gas::Result<Self> {
        ChainEngine::from_state(state)
    }
}
