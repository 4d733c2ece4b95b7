//! The homogeneous DSMC engine: velocities only, exact serial or blocked parallel. The
//! exact scheme runs the process with the speed-class majorants of [`classes`] (about 1.5
//! candidates per collision instead of the kernel's 4); the blocks keep the kernel's single
//! majorant, which is faster there (see [`blocks`]). The block scheme spreads over ranks,
//! each holding a run of whole blocks.

mod blocks;
mod classes;
mod spin;

use super::domain::Traffic;
use super::kernel::{
    self, add_counts, Collider, Moments, OneSpecies, Record, SpeciesTag, SpeciesTally, Spun,
    Tagged, Window,
};
use super::reduce;
use super::rough::Spin;
use super::species::{by_species, Species};
use super::{check_input, mean_velocity, HomogeneousSnapshot, Scheme};
use crate::driving::{Drive, Driving};
use crate::engine::{Checkpoint, Counters, Engine, SpeciesCollisions, VelocityStatistics};
use crate::error::{Error, Result};
use crate::parallel::{Communicator, Local, RankReport};
use crate::rng::{Purpose, Stream};
use crate::shear::{Shear, Virial};
use crate::system::{System, Vector};
use crate::tail::Tail;
use crate::theory;
use blocks::{run_blocks, Blocks};
use classes::{class_width, Classes, ShearFrame};
use restitution::Restitution;
use std::sync::Arc;

/// The particle records, with a second buffer for the block re-mixing.
enum Store<const D: usize> {
    /// One species: the velocity is the record (8 D bytes).
    Uniform(Vec<Vector<D>>, Vec<Vector<D>>),
    Mixed(Vec<Tagged<D>>, Vec<Tagged<D>>),
    /// Rough particles: velocity, species and angular velocity.
    Rough(Vec<Spun<D>>, Vec<Spun<D>>),
    /// Rough particles of one species: velocity and angular velocity.
    RoughUniform(Vec<Spun<D, OneSpecies>>, Vec<Spun<D, OneSpecies>>),
}

/// `$body` with `$now` and `$spare` bound to the records and the spare buffer of the
/// store, whichever their kind (the body is compiled for each).
macro_rules! each_store {
    ($store:expr, ($now:pat, $spare:pat) => $body:expr) => {
        match $store {
            Store::Uniform($now, $spare) => $body,
            Store::Mixed($now, $spare) => $body,
            Store::Rough($now, $spare) => $body,
            Store::RoughUniform($now, $spare) => $body,
        }
    };
}
use each_store;

/// Everything but the records.
struct Core<const D: usize> {
    species: Species,
    law: Box<dyn Restitution>,
    /// The law of each pair of species (pairwise laws; [`super::species::engine_laws`]).
    pairs: Option<Vec<Box<dyn Restitution>>>,
    scheme: Scheme,
    phi: f64,
    seed: u64,
    /// N times the mean sphere volume over phi (the box of the event-driven engine).
    volume: f64,
    reference: Vector<D>,
    time: f64,
    steps: u64,
    tally: Counters,
    /// Collisions of each species' particles (mixtures; empty for one species).
    species_collisions: Vec<u64>,
    /// Driving (block scheme): white-noise kicks around each step's collisions, or the
    /// thermostat's scaling after each step.
    driving: Option<Driving>,
    /// The velocity speed bounds are measured from: the mean velocity when the exact
    /// scheme last recomputed its bound, or at the end of the last block step.
    /// [`Scheme::Exact`]: also the bound on |v - reference| and the stream.
    speed_bound: f64,
    stream: Stream,
    /// Blocks: the temperature at the end of the last step (sets the step and the class
    /// width); exact: at the last recompute of the bound (sets the class width).
    temperature: f64,
    /// [`Scheme::Exact`]: the speed classes of the records (sorted by class) and the class
    /// of each record; `None` until the first run after a start, a restore or a recompute
    /// of the bound (the sort is then the identity on records saved sorted).
    classes: Option<Classes>,
    class: Vec<u8>,
    /// The ranks the run is spread over ([`Local`]: this process alone; only the block
    /// scheme spreads), the particles of all ranks, and this rank's communication.
    comm: Arc<dyn Communicator>,
    total: usize,
    traffic: Traffic,
    /// Uniform shear flow in the frame moving with it (block scheme; see [`blocks`]).
    shear: Option<Shear>,
    /// The tensor virial of the collisions, if summed.
    virial: Option<Virial>,
    /// Rough particles ([`Store::Rough`]).
    spin: Option<Spin>,
}

/// The collider of a core's law, species and spins (a function of the fields, so that
/// the core's other fields stay free to borrow).
fn collider<'a>(
    law: &'a dyn Restitution,
    species: &'a Species,
    pairs: Option<&'a [Box<dyn Restitution>]>,
    spin: Option<&'a Spin>,
) -> Collider<'a> {
    Collider {
        law,
        species,
        pairs,
        rough: spin.and_then(Spin::kernel),
    }
}

/// A record of the homogeneous engine as it travels between ranks: its velocity, then its
/// species for mixtures (`VALUES` f64 values).
pub(crate) trait HomogeneousRecord<const D: usize>: Record<D> {
    const VALUES: usize = D + Self::MIXED as usize;
    fn from_parts(velocity: Vector<D>, species: u32) -> Self;

    fn encode(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(self.velocity());
        if Self::MIXED {
            out.push(self.species() as f64);
        }
    }

    fn decode(row: &[f64]) -> Self {
        let species = if Self::MIXED { row[D] as u32 } else { 0 };
        Self::from_parts(std::array::from_fn(|k| row[k]), species)
    }
}

impl<const D: usize> HomogeneousRecord<D> for Vector<D> {
    fn from_parts(velocity: Vector<D>, _species: u32) -> Self {
        velocity
    }
}

impl<const D: usize> HomogeneousRecord<D> for Tagged<D> {
    fn from_parts(velocity: Vector<D>, species: u32) -> Self {
        Tagged { velocity, species }
    }
}

/// Rough records travel as velocity, species, angular velocity (D + 4 values, the
/// species 0 for a gas of one species).
impl<const D: usize, S: SpeciesTag> HomogeneousRecord<D> for Spun<D, S> {
    const VALUES: usize = D + 4;
    fn from_parts(velocity: Vector<D>, species: u32) -> Self {
        Spun {
            velocity,
            species: S::of(species),
            angular: [0.0; 3],
        }
    }

    fn encode(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(&self.velocity);
        out.push(self.species.index() as f64);
        out.extend_from_slice(&self.angular);
    }

    fn decode(row: &[f64]) -> Self {
        Spun {
            velocity: std::array::from_fn(|k| row[k]),
            species: S::of(row[D] as u32),
            angular: [row[D + 1], row[D + 2], row[D + 3]],
        }
    }
}

/// DSMC of a spatially homogeneous granular gas (see the [module](super) documentation).
///
/// The collision rate of a pair is g2(phi) sigma^(D-1) c_D |g| / V with V the volume in which
/// the spheres fill the packing fraction phi (the event-driven engine's box for a system
/// from `init::monodisperse`), so times agree with the event-driven engine (Enskog).
pub struct HomogeneousDsmc<const D: usize> {
    core: Core<D>,
    store: Store<D>,
    /// Output buffer of [`HomogeneousDsmc::system`].
    system: System<D>,
    /// Output buffer of the rotation (rough particles).
    rotation: Option<crate::rotation::Rotation>,
}

impl<const D: usize> HomogeneousDsmc<D> {
    /// An engine at time 0 from the velocities, radii and masses of `system` (positions are
    /// ignored), the packing fraction `phi` (0 < phi < close packing), the law, a seed and the
    /// scheme. Fails, naming the parameter, for bad input.
    pub fn new(
        system: System<D>,
        phi: f64,
        law: Box<dyn Restitution>,
        seed: u64,
        scheme: Scheme,
    ) -> Result<Self> {
        Self::distributed(system, phi, law, seed, scheme, Arc::new(Local))
    }

    /// The engine of [`HomogeneousDsmc::new`] spread over the ranks of `comm` (every rank
    /// calls this with the same arguments): the block scheme only, each rank holding a run
    /// of whole blocks. Its run is the single process's, bit for bit, on any number of
    /// ranks. Fails (`ranks`) for the exact scheme on several ranks and for more ranks than
    /// blocks.
    pub fn distributed(
        system: System<D>,
        phi: f64,
        law: Box<dyn Restitution>,
        seed: u64,
        scheme: Scheme,
        comm: Arc<dyn Communicator>,
    ) -> Result<Self> {
        check_input(&system, phi)?;
        check_scheme(&scheme)?;
        let n = system.velocities.len();
        let ranks = comm.size();
        let share = match scheme {
            Scheme::Blocks { block_size, .. } => {
                let layout = Blocks::new(n, block_size);
                if ranks > layout.count {
                    return Err(Error::TooManyRanks {
                        ranks,
                        allowed: format!("at most the {} blocks of the gas", layout.count),
                    });
                }
                let share = layout.share(comm.rank(), ranks);
                Some((layout.start(share.first), layout.start(share.end)))
            }
            Scheme::Exact if ranks > 1 => {
                return Err(Error::TooManyRanks {
                    ranks,
                    allowed: "1: the exact scheme is one serial process (the block scheme spreads)"
                        .into(),
                })
            }
            Scheme::Exact => None,
        };
        let (species, index) = Species::of::<D>(&system.radii, &system.masses, phi)?;
        let (law, pairs) = super::species::engine_laws(law, &species)?;
        let reference = mean_velocity(&system.velocities, &system.masses);
        let n = system.velocities.len();
        let mut core = Core {
            volume: species.sphere_volume / phi,
            species,
            law,
            pairs,
            scheme,
            phi,
            seed,
            reference,
            time: 0.0,
            steps: 0,
            tally: Counters::default(),
            species_collisions: Vec::new(),
            driving: None,
            speed_bound: 0.0,
            stream: Stream::new(seed, Purpose::Exact, 0, 0),
            temperature: 0.0,
            classes: None,
            class: Vec::new(),
            comm,
            total: n,
            traffic: Traffic::default(),
            shear: None,
            virial: None,
            spin: None,
        };
        let mut store = make_store(&core.species, system.velocities, &index);
        let (bound, moments) = each_store!(&store, (now, _) => (
            kernel::speed_bound(now, &reference),
            Moments::of(now, &core.species),
        ));
        core.speed_bound = bound;
        core.temperature = moments.spread / (n * D) as f64;
        if let (Some((first, end)), true) = (share, ranks > 1) {
            // Every rank built the whole gas (the same numbers); keep this rank's blocks.
            each_store!(&mut store, (now, _) => keep(now, first, end))
        }
        let mut engine = HomogeneousDsmc {
            core,
            store,
            system: empty_system(),
            rotation: None,
        };
        if engine.core.law.tangential().is_some() {
            // Rough particles start as solid spheres (disks) at rest until given their
            // rotation (collective: every rank takes its share of the same rotation).
            let solid = vec![0.4; engine.core.species.len()];
            engine.give_rotation(vec![[0.0; 3]; n], solid, 0);
        }
        Ok(engine)
    }

    /// The engine of `snapshot` over the ranks of `comm` (every rank reads the same
    /// snapshot, from any number of ranks, and keeps its blocks), bit for bit the single
    /// process's run. The snapshot is checked first ([`HomogeneousSnapshot::check`]).
    pub fn restore_distributed(
        snapshot: HomogeneousSnapshot<D>,
        law: Box<dyn Restitution>,
        comm: Arc<dyn Communicator>,
    ) -> Result<Self> {
        snapshot.check(true)?;
        if matches!(snapshot.options, Scheme::Blocks { .. }) {
            snapshot.check_step_temperature()?;
        }
        snapshot.check_reference_velocity()?;
        let HomogeneousSnapshot {
            system,
            packing_fraction,
            seed,
            options,
            time,
            steps,
            counters: tally,
            reference_velocity,
            speed_bound,
            draws,
            temperature,
            species_collisions,
            tail,
        } = snapshot;
        if tail.walls.is_some() {
            return Err(Error::out_of_range(
                "walls",
                "a container",
                "none: homogeneous DSMC has no positions, so no walls",
            ));
        }
        let mut engine = Self::distributed(system, packing_fraction, law, seed, options, comm)?;
        engine.set_shear_of(tail.shear)?;
        // The exact scheme's majorant (finite: `Snapshot::check`) must bound every speed (it
        // only ever grows to the largest one seen): a smaller one would accept with
        // probabilities above 1.
        if matches!(options, Scheme::Exact) {
            let largest = each_store!(&engine.store, (now, _) => kernel::speed_bound(now, &reference_velocity));
            if speed_bound < largest {
                return Err(Error::out_of_range(
                    "speed_bound",
                    speed_bound,
                    format!("at least the largest |v - reference_velocity|, {largest}"),
                ));
            }
        }
        let core = &mut engine.core;
        core.time = time;
        core.steps = steps;
        core.tally = tally;
        core.reference = reference_velocity;
        core.speed_bound = speed_bound;
        core.stream = Stream::at(seed, Purpose::Exact, 0, 0, draws);
        core.temperature = temperature;
        core.species_collisions = species_collisions;
        core.virial = tail.virial;
        if let Some(rotation) = tail.rotation {
            engine.set_rotation_of(Some(rotation))?;
        }
        Ok(engine)
    }

    /// The state, random stream positions and options, to continue later bit for bit.
    pub fn snapshot(&mut self) -> HomogeneousSnapshot<D> {
        let system = self.system().clone();
        let rotation = self.rotation_now().cloned();
        let c = &self.core;
        let (time, steps, tally, seed, scheme, phi) =
            (c.time, c.steps, c.tally, c.seed, c.scheme, c.phi);
        let (reference, speed_bound, draws, temperature) =
            (c.reference, c.speed_bound, c.stream.draws(), c.temperature);
        let species_collisions = super::species::in_saved_order(
            &c.species,
            &c.species_collisions,
            &system.radii,
            &system.masses,
        );
        let tail = Tail {
            shear: c.shear,
            virial: c.virial,
            rotation,
            ..Default::default()
        };
        HomogeneousSnapshot {
            system,
            packing_fraction: phi,
            seed,
            options: scheme,
            time,
            steps,
            counters: tally,
            reference_velocity: reference,
            speed_bound,
            draws,
            temperature,
            species_collisions,
            tail,
        }
    }

    /// Shears the gas (None: no more): the USF in the frame moving with the flow, whose
    /// peculiar velocities obey dV_x/dt = -a V_y between collisions: the block scheme
    /// streams them exactly around each step's collisions (module [`blocks`]); the exact
    /// scheme collides each pair at its time with the streamed velocities
    /// ([`classes::ShearFrame`]), exact in the frame.
    fn set_shear_of(&mut self, shear: Option<Shear>) -> Result<()> {
        if let Some(s) = &shear {
            s.check_for::<D>()?;
        }
        self.core.shear = shear;
        Ok(())
    }

    /// Steps of [`Scheme::Blocks`] so far (0 for the exact scheme).
    pub fn steps(&self) -> u64 {
        self.core.steps
    }

    /// The particles of all ranks.
    pub fn len(&self) -> usize {
        self.core.total
    }

    /// The ranks the engine is spread over.
    pub fn ranks(&self) -> usize {
        self.core.comm.size()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The volume V of the gas (N sphere volumes over phi).
    pub fn volume(&self) -> f64 {
        self.core.volume
    }

    /// The temperature at the end of the last step (blocks) or at the last recompute of the
    /// speed bound, every N collisions (exact); use `observe::temperature(self.system())`
    /// for the current one.
    pub fn step_temperature(&self) -> f64 {
        self.core.temperature
    }

    fn run(&mut self, end: f64, target: u64, pause: u64) {
        let core = &mut self.core;
        each_store!(&mut self.store, (now, spare) => run_records(core, now, spare, end, target, pause))
    }
}

fn check_scheme(scheme: &Scheme) -> Result<()> {
    match scheme {
        Scheme::Exact => Ok(()),
        Scheme::Blocks { block_size, step } => {
            if *block_size < 2 || *block_size > u32::MAX as usize {
                return Err(Error::out_of_range(
                    "block_size",
                    block_size,
                    format!("2 ..= {}", u32::MAX),
                ));
            }
            step.check()
        }
    }
}

fn empty_system<const D: usize>() -> System<D> {
    System {
        sides: [0.0; D],
        positions: Vec::new(),
        velocities: Vec::new(),
        radii: Vec::new(),
        masses: Vec::new(),
    }
}

fn make_store<const D: usize>(
    species: &Species,
    velocities: Vec<Vector<D>>,
    index: &[u32],
) -> Store<D> {
    if species.len() == 1 {
        Store::Uniform(velocities, Vec::new())
    } else {
        let records = velocities
            .into_iter()
            .zip(index)
            .map(|(velocity, &species)| Tagged { velocity, species })
            .collect();
        Store::Mixed(records, Vec::new())
    }
}

/// Keeps the records `first..end` of `records`.
fn keep<R>(records: &mut Vec<R>, first: usize, end: usize) {
    records.truncate(end);
    records.drain(..first);
    records.shrink_to_fit();
}

/// The records of all ranks in order (collective; this rank's own on one rank).
fn gathered<'a, const D: usize, R: HomogeneousRecord<D>>(
    records: &'a [R],
    core: &mut Core<D>,
) -> std::borrow::Cow<'a, [R]> {
    if core.comm.size() == 1 {
        return std::borrow::Cow::Borrowed(records);
    }
    let clock = std::time::Instant::now();
    let mut mine = Vec::with_capacity(R::VALUES * records.len());
    records.iter().for_each(|r| r.encode(&mut mine));
    let all = core.comm.all_gather(mine);
    let gathered = all
        .iter()
        .flat_map(|v| v.chunks_exact(R::VALUES))
        .map(R::decode)
        .collect();
    core.traffic.gather_seconds += clock.elapsed().as_secs_f64();
    std::borrow::Cow::Owned(gathered)
}

fn fill<const D: usize, R: Record<D>>(s: &mut System<D>, records: &[R], species: &Species) {
    for r in records {
        s.velocities.push(*r.velocity());
        s.radii.push(species.radii[r.species()]);
        s.masses.push(species.masses[r.species()]);
    }
}

fn run_records<const D: usize, R: HomogeneousRecord<D>>(
    core: &mut Core<D>,
    now: &mut Vec<R>,
    spare: &mut Vec<R>,
    end: f64,
    target: u64,
    pause: u64,
) {
    match core.scheme {
        // The exact scheme stops at a collision: pausing there is stopping there.
        Scheme::Exact => run_exact(core, now, end, target.min(pause)),
        Scheme::Blocks { block_size, step } => {
            run_blocks(core, now, spare, block_size, step, end, target, pause)
        }
    }
}

/// The exact scheme: the speed-class process over all particles (records kept sorted by
/// class), its speed bound, reference velocity, temperature and classes recomputed from
/// scratch (about the current mean velocity) after every N collisions: the bound only ever
/// rises inside the kernel, while inelastic collisions slow particles down.
fn run_exact<const D: usize, R: Record<D>>(
    core: &mut Core<D>,
    records: &mut [R],
    end: f64,
    target: u64,
) {
    let n = records.len() as u64;
    let pair_rate = theory::cross_section_factor::<D>() * core.species.max_weight / core.volume;
    while core.tally.collisions < target && core.time < end {
        if core.speed_bound == 0.0 {
            // Nothing moves relative to the rest: no collision ever.
            if end.is_finite() {
                if let Some(shear) = core.shear {
                    stream_sheared(records, shear.rate * (end - core.time));
                }
                core.time = end;
            }
            return;
        }
        let next_recompute = (core.tally.collisions / n + 1) * n;
        // Under shear a window lasts at most SHEARED_EXACT_STRAIN / |a|: the majorant grows
        // by that factor over it (`run_classes_sheared`).
        let window_end = match core.shear {
            Some(shear) => end.min(core.time + SHEARED_EXACT_STRAIN / shear.rate.abs()),
            None => end,
        };
        let window = Window {
            start: core.time,
            end: window_end,
            max_collisions: target.min(next_recompute) - core.tally.collisions,
        };
        let collider = collider(
            core.law.as_ref(),
            &core.species,
            core.pairs.as_deref(),
            core.spin.as_ref(),
        );
        let classes = core.classes.get_or_insert_with(|| {
            let width = class_width(core.temperature, core.species.min_mass, core.speed_bound);
            Classes::sort(
                records,
                &mut core.class,
                &core.reference,
                width,
                core.speed_bound,
            )
        });
        let mut tally = SpeciesTally::new(core.species.len());
        tally.counters = core.tally;
        tally.virial = core.virial;
        let start = core.time;
        core.time = match core.shear {
            None => collider.run_classes(
                records,
                &mut core.class,
                classes,
                &core.reference,
                pair_rate,
                window,
                &mut core.stream,
                &mut tally,
            ),
            Some(shear) => collider.run_classes_sheared(
                records,
                &mut core.class,
                classes,
                &core.reference,
                pair_rate,
                window,
                &mut core.stream,
                &mut tally,
                ShearFrame {
                    rate: shear.rate,
                    anchor: start,
                },
            ),
        };
        core.tally = tally.counters;
        core.virial = tally.virial;
        if let Some(spin) = &mut core.spin {
            spin.sliding += tally.sliding;
        }
        add_counts(&mut core.species_collisions, &tally.collisions);
        core.speed_bound = classes.bound();
        if let Some(shear) = core.shear {
            // The records back to the velocities now (the frame anchored here), with the
            // bound and classes anew.
            stream_sheared(records, shear.rate * (core.time - start));
            let moments = Moments::of(records, &core.species);
            core.reference = moments.mean();
            core.temperature = moments.spread / (n as usize * D) as f64;
            core.speed_bound = kernel::speed_bound(records, &core.reference);
            core.classes = None;
        } else if core.tally.collisions == next_recompute {
            let moments = Moments::of(records, &core.species);
            core.reference = moments.mean();
            core.temperature = moments.spread / (n as usize * D) as f64;
            core.speed_bound = kernel::speed_bound(records, &core.reference);
            core.classes = None;
        }
    }
}

/// The strain |a| Δt of one window of the exact scheme under shear: the majorant is
/// 1 + this times the largest rate (10 % more candidates), and the records are streamed
/// and re-sorted at its end (O(N) every 0.1 / |a|).
const SHEARED_EXACT_STRAIN: f64 = 0.1;

/// Streams peculiar velocities by the strain a τ of the uniform shear flow:
/// V_x -= a τ V_y (exact between collisions).
fn stream_sheared<const D: usize, R: Record<D>>(records: &mut [R], strain: f64) {
    for r in records {
        let v = r.velocity_mut();
        v[0] -= strain * v[1];
    }
}

impl<const D: usize> Engine<D> for HomogeneousDsmc<D> {
    /// Runs until the time reaches `t` (no effect if it already has).
    fn run_until(&mut self, t: f64) {
        self.run(t, u64::MAX, u64::MAX);
    }

    /// Runs until `collisions` more collisions have happened. The exact scheme stops at
    /// the collision; the block scheme at the end of a step, its last steps shortened to the
    /// expected remaining count (overshoot of order its square root). Stops early if
    /// nothing can collide (all particles at rest relative to each other).
    fn run_collisions(&mut self, collisions: u64) {
        let target = self.core.tally.collisions.saturating_add(collisions);
        self.run(f64::INFINITY, target, u64::MAX);
    }

    /// Runs toward `end` and `collisions`, pausing where the tally reaches `pause` (the
    /// blocks scheme at the end of a step; see [`crate::Engine::run_paused`]).
    fn run_paused(&mut self, end: f64, collisions: u64, pause: u64) {
        self.run(end, collisions, pause);
    }

    fn time(&self) -> f64 {
        self.core.time
    }

    fn counters(&self) -> Counters {
        self.core.tally
    }

    /// The current state: velocities, radii and masses in the engine's current order (the
    /// block scheme permutes particles every step), positions all zero, the box the cube of
    /// volume V. For `observe::{temperature, sonine_a2, ...}`. On several ranks,
    /// collective: the blocks of all ranks in order.
    fn system(&mut self) -> &System<D> {
        let core = &mut self.core;
        let s = &mut self.system;
        s.sides = [core.volume.powf(1.0 / D as f64); D];
        s.velocities.clear();
        s.radii.clear();
        s.masses.clear();
        each_store!(&self.store, (now, _) => fill(s, &gathered(now, core), &core.species));
        s.positions.clear();
        s.positions.resize(s.velocities.len(), [0.0; D]);
        &self.system
    }

    /// The collisions of each species' particles so far (each collision counts for both).
    fn species_collisions(&self) -> Option<Vec<SpeciesCollisions>> {
        Some(by_species(
            &self.core.species,
            &self.core.species_collisions,
            &self.core.tally,
        ))
    }

    /// Every rank's particles, blocks and communication so far (collective); None on one
    /// rank.
    fn rank_reports(&self) -> Option<Vec<RankReport>> {
        let core = &self.core;
        let blocks = match core.scheme {
            Scheme::Blocks { block_size, .. } => {
                let share =
                    Blocks::new(core.total, block_size).share(core.comm.rank(), core.comm.size());
                share.end - share.first
            }
            Scheme::Exact => 0,
        };
        let particles = each_store!(&self.store, (now, _) => now.len());
        core.traffic
            .reports(core.comm.as_ref(), particles, blocks as u64)
    }

    /// The temperature and Sonine a2 of all particles, and the volume, from exact sums over
    /// the particles of all ranks (collective; the same bits on any number of ranks).
    fn velocity_statistics(&mut self) -> Option<VelocityStatistics> {
        let core = &mut self.core;
        let (species, total, volume) = (&core.species, core.total, core.volume);
        let (comm, traffic) = (core.comm.as_ref(), &mut core.traffic);
        Some(each_store!(&self.store, (now, _) => {
            reduce::velocity_statistics(now, species, total, volume, comm, traffic)
        }))
    }

    /// Bytes held by the engine: records, the re-mixing buffer, the classes of the exact
    /// scheme (a byte per particle), the output of [`HomogeneousDsmc::system`] once taken,
    /// and the species tables.
    fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        fn bytes<T>(a: &Vec<T>, b: &Vec<T>) -> usize {
            (a.capacity() + b.capacity()) * std::mem::size_of::<T>()
        }
        let records = each_store!(&self.store, (a, b) => bytes(a, b));
        let s = &self.system;
        let output = (s.positions.capacity() + s.velocities.capacity()) * size_of::<Vector<D>>()
            + (s.radii.capacity() + s.masses.capacity()) * size_of::<f64>();
        records + self.core.class.capacity() + output + self.core.species.memory_bytes()
    }

    fn particles(&self) -> usize {
        self.len()
    }

    /// Shears the gas from now on (block scheme; see [`HomogeneousDsmc::set_shear_of`]).
    fn set_shear(&mut self, shear: Option<Shear>) -> Result<()> {
        self.set_shear_of(shear)
    }

    fn shear(&self) -> Option<Shear> {
        self.core.shear
    }

    fn virial_tensor(&self) -> Option<Virial> {
        self.core.virial
    }

    /// Sums the tensor virial of the collisions (Enskog's collisional transfer: the
    /// impact direction's n n), from zero unless summed already.
    fn set_virial_tensor(&mut self, on: bool) -> Result<()> {
        if !on {
            self.core.virial = None;
        } else if self.core.virial.is_none() {
            self.core.virial = Some(Virial::default());
        }
        Ok(())
    }

    /// Gives the particles `rotation` in the order of [`Engine::system`] (collective);
    /// the inertia factor must be one per species.
    fn set_rotation(&mut self, rotation: Option<crate::rotation::Rotation>) -> Result<()> {
        self.set_rotation_of(rotation)
    }

    /// The particles' rotation in the order of [`Engine::system`] (collective).
    fn rotation(&mut self) -> Option<&crate::rotation::Rotation> {
        self.rotation_now()
    }

    /// Rough particles: the section `rotation` (contacts that slid, all ranks).
    fn report(&self) -> crate::engine::Report {
        crate::engine::Report {
            sections: self
                .core
                .spin
                .as_ref()
                .map(|spin| {
                    let r = crate::rotation::Rotation {
                        inertia: Vec::new(),
                        angular: Vec::new(),
                        sliding: spin.sliding,
                    };
                    r.report(self.core.tally.collisions)
                })
                .into_iter()
                .collect(),
        }
    }

    /// Drives the gas from now on (None: freely cooling) at every step of the block scheme;
    /// fails (`driving`) for the exact scheme and (`interval`) for an interval: the steps
    /// are the kick interval. Not part of the snapshot: set it again after a restore.
    fn set_driving(&mut self, drive: Option<Drive>) -> Result<()> {
        if let Some(interval) = drive.and_then(|d| d.interval) {
            return Err(Error::out_of_range(
                "interval",
                interval,
                "none: the DSMC drives at every step",
            ));
        }
        if drive.is_some() && matches!(self.core.scheme, Scheme::Exact) {
            return Err(Error::out_of_range(
                "driving",
                "the exact scheme",
                "the block scheme (its steps are the kick interval)",
            ));
        }
        self.core.driving = drive.map(|d| d.driving);
        Ok(())
    }
}

impl<const D: usize> Checkpoint<D> for HomogeneousDsmc<D> {
    type State = HomogeneousSnapshot<D>;
    /// The collision law.
    type Needs = Box<dyn Restitution>;

    fn save(&mut self) -> HomogeneousSnapshot<D> {
        self.snapshot()
    }

    /// Continues the run of `state` bit for bit with the law it used, in this process
    /// ([`HomogeneousDsmc::restore_distributed`] over ranks).
    fn restore(state: HomogeneousSnapshot<D>, law: Box<dyn Restitution>) -> Result<Self> {
        Self::restore_distributed(state, law, Arc::new(Local))
    }
}
