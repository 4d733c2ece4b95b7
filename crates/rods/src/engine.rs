//! The rod chain behind the engine interface of `gas` ([`gas::Engine`], [`gas::Checkpoint`]):
//! what applies to a Hamiltonian chain. A collision is an impact (counted from contact
//! episodes by [`Impacts`]); events are contact episodes; no energy is dissipated (the
//! translational energy an impact loses goes into the modes: see [`Chain::energy`] and
//! [`Chain::modal_energies`]), so `energy_lost` and the virial stay 0. The state seen by
//! observers is the rods as hard rods: centres in [0, P), centre-of-mass velocities,
//! radius l/2, mass rho l.

use crate::chain::{Chain, Impacts};
use gas::{Checkpoint, Counters, Engine, System};
use serde::{Deserialize, Serialize};

/// A rod chain with its impact counter.
#[derive(Debug, Clone)]
pub struct ChainEngine {
    chain: Chain,
    impacts: Impacts,
    episodes: u64,
    system: System<1>,
}

/// The complete state of a [`ChainEngine`] (the chain serializes completely).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainEngineState {
    pub chain: Chain,
    pub impacts: Impacts,
    pub episodes: u64,
}

impl ChainEngine {
    /// The engine of `chain`, no impacts counted yet.
    pub fn new(chain: Chain) -> Self {
        let rods = chain.n_rods();
        ChainEngine {
            chain,
            impacts: Impacts::new(rods),
            episodes: 0,
            system: System {
                length: 0.0,
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
        let records = self.chain.run_until(t);
        self.count(&records);
    }

    /// Runs contact episodes until `collisions` more impacts have been counted.
    fn run_collisions(&mut self, collisions: u64) {
        let target = self.impacts.collisions() + collisions;
        while self.impacts.collisions() < target {
            let records = self.chain.run_collisions(1);
            if records.is_empty() {
                break;
            }
            self.count(&records);
        }
    }

    fn time(&self) -> f64 {
        self.chain.time()
    }

    fn counters(&self) -> Counters {
        Counters {
            collisions: self.impacts.collisions(),
            events: self.episodes,
            ..Counters::default()
        }
    }

    fn particles(&self) -> usize {
        self.chain.n_rods()
    }

    fn system(&mut self) -> &System<1> {
        let perimeter = self.chain.perimeter();
        let s = &mut self.system;
        s.length = perimeter;
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
        }
    }

    /// Restores the chain after checking it ([`ChainEngine::from_state`]).
    fn restore(state: ChainEngineState, _needs: ()) -> gas::Result<Self> {
        ChainEngine::from_state(state)
    }
}
