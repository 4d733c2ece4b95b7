//! The homogeneous DSMC engine: velocities only, exact serial or blocked parallel. The
//! exact scheme runs the process with the speed-class majorants of [`classes`] (about 1.5
//! candidates per collision instead of the kernel's 4); the blocks keep the kernel's single
//! majorant, which is faster there (see [`block_step`]).

mod classes;

use super::kernel::{self, Collider, Moments, Record, Tagged, Window};
use super::species::Species;
use super::{
    check_input, frequency_estimate, mean_velocity, positive, HomogeneousSnapshot, Scheme,
    StepSize, DEFAULT_BLOCK_COLLISIONS_PER_STEP,
};
use crate::engine::Counters;
use crate::error::{Error, Result};
use crate::rng::{Purpose, Stream};
use crate::system::{dot, System, Vector};
use crate::theory;
use classes::{class_width, Classes};
use rayon::prelude::*;
use restitution::Restitution;

/// Particles per lane of the block re-mixing: a lane moves to another block as a whole.
const LANE: usize = 16;

/// The particle records, with a second buffer for the block re-mixing.
enum Store<const D: usize> {
    /// One species: the velocity is the record (8 D bytes).
    Uniform(Vec<Vector<D>>, Vec<Vector<D>>),
    Mixed(Vec<Tagged<D>>, Vec<Tagged<D>>),
}

/// Everything but the records.
struct Core<const D: usize> {
    species: Species,
    law: Box<dyn Restitution>,
    scheme: Scheme,
    phi: f64,
    seed: u64,
    /// N times the mean sphere volume over phi (the box of the event-driven engine).
    volume: f64,
    reference: Vector<D>,
    time: f64,
    steps: u64,
    tally: Counters,
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
        check_input(&system, phi)?;
        check_scheme(&scheme)?;
        let (species, index) = Species::of::<D>(&system.radii, &system.masses, phi)?;
        let reference = mean_velocity(&system.velocities, &system.masses);
        let n = system.velocities.len();
        let mut core = Core {
            volume: species.sphere_volume / phi,
            species,
            law,
            scheme,
            phi,
            seed,
            reference,
            time: 0.0,
            steps: 0,
            tally: Counters::default(),
            speed_bound: 0.0,
            stream: Stream::new(seed, Purpose::Exact, 0, 0),
            temperature: 0.0,
            classes: None,
            class: Vec::new(),
        };
        let store = make_store(&core.species, system.velocities, &index);
        let (bound, moments) = match &store {
            Store::Uniform(now, _) => (
                kernel::speed_bound(now, &reference),
                Moments::of(now, &core.species),
            ),
            Store::Mixed(now, _) => (
                kernel::speed_bound(now, &reference),
                Moments::of(now, &core.species),
            ),
        };
        core.speed_bound = bound;
        core.temperature = moments.spread / (n * D) as f64;
        Ok(HomogeneousDsmc {
            core,
            store,
            system: empty_system(),
        })
    }

    /// Continues the run of `snapshot` bit for bit with the law it used.
    pub fn restore(snapshot: HomogeneousSnapshot<D>, law: Box<dyn Restitution>) -> Result<Self> {
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
        } = snapshot;
        let mut engine = Self::new(system, packing_fraction, law, seed, options)?;
        // The exact scheme's majorant (finite: `Snapshot::check`) must bound every speed (it
        // only ever grows to the largest one seen): a smaller one would accept with
        // probabilities above 1.
        if matches!(options, Scheme::Exact) {
            let largest = match &engine.store {
                Store::Uniform(now, _) => kernel::speed_bound(now, &reference_velocity),
                Store::Mixed(now, _) => kernel::speed_bound(now, &reference_velocity),
            };
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
        Ok(engine)
    }

    /// The state, random stream positions and options, to continue later bit for bit.
    pub fn snapshot(&mut self) -> HomogeneousSnapshot<D> {
        let c = &self.core;
        let (time, steps, tally, seed, scheme, phi) =
            (c.time, c.steps, c.tally, c.seed, c.scheme, c.phi);
        let (reference, speed_bound, draws, temperature) =
            (c.reference, c.speed_bound, c.stream.draws(), c.temperature);
        HomogeneousSnapshot {
            system: self.system().clone(),
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
        }
    }

    pub fn time(&self) -> f64 {
        self.core.time
    }

    pub fn counters(&self) -> Counters {
        self.core.tally
    }

    /// Steps of [`Scheme::Blocks`] so far (0 for the exact scheme).
    pub fn steps(&self) -> u64 {
        self.core.steps
    }

    pub fn len(&self) -> usize {
        match &self.store {
            Store::Uniform(now, _) => now.len(),
            Store::Mixed(now, _) => now.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Collisions per particle so far (each collision counts for two particles).
    pub fn collisions_per_particle(&self) -> f64 {
        2.0 * self.core.tally.collisions as f64 / self.len() as f64
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

    /// The current state: velocities, radii and masses in the engine's current order (the
    /// block scheme permutes particles every step), positions all zero, `length` the side of
    /// the cube of volume V. For `observe::{temperature, sonine_a2, ...}`.
    pub fn system(&mut self) -> &System<D> {
        let species = &self.core.species;
        let s = &mut self.system;
        s.length = self.core.volume.powf(1.0 / D as f64);
        s.velocities.clear();
        s.radii.clear();
        s.masses.clear();
        match &self.store {
            Store::Uniform(now, _) => fill(s, now, species),
            Store::Mixed(now, _) => fill(s, now, species),
        }
        s.positions.clear();
        s.positions.resize(s.velocities.len(), [0.0; D]);
        &self.system
    }

    /// None: the homogeneous engine runs in one process.
    pub fn rank_reports(&self) -> Option<Vec<crate::parallel::RankReport>> {
        None
    }

    /// None: computed from the system.
    pub fn velocity_statistics(&mut self) -> Option<crate::engine::VelocityStatistics> {
        None
    }

    /// Bytes held by the engine: records, the re-mixing buffer, the classes of the exact
    /// scheme (a byte per particle), the output of [`HomogeneousDsmc::system`] once taken,
    /// and the species tables.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let records = match &self.store {
            Store::Uniform(a, b) => (a.capacity() + b.capacity()) * size_of::<Vector<D>>(),
            Store::Mixed(a, b) => (a.capacity() + b.capacity()) * size_of::<Tagged<D>>(),
        };
        let s = &self.system;
        let output = (s.positions.capacity() + s.velocities.capacity()) * size_of::<Vector<D>>()
            + (s.radii.capacity() + s.masses.capacity()) * size_of::<f64>();
        records + self.core.class.capacity() + output + self.core.species.memory_bytes()
    }

    /// Runs until `collisions` more collisions have happened. The exact scheme stops at
    /// the collision; the block scheme at the end of a step, its last steps shortened to the
    /// expected remaining count (overshoot of order its square root). Stops early if
    /// nothing can collide (all particles at rest relative to each other).
    pub fn run_collisions(&mut self, collisions: u64) {
        let target = self.core.tally.collisions.saturating_add(collisions);
        self.run(f64::INFINITY, target, u64::MAX);
    }

    /// Runs until the time reaches `t` (no effect if it already has).
    pub fn run_until(&mut self, t: f64) {
        self.run(t, u64::MAX, u64::MAX);
    }

    /// Runs toward `end` and `collisions`, pausing where the tally reaches `pause` (the
    /// blocks scheme at the end of a step; see [`crate::Engine::run_paused`]).
    pub fn run_paused(&mut self, end: f64, collisions: u64, pause: u64) {
        self.run(end, collisions, pause);
    }

    fn run(&mut self, end: f64, target: u64, pause: u64) {
        let core = &mut self.core;
        match &mut self.store {
            Store::Uniform(now, spare) => run_records(core, now, spare, end, target, pause),
            Store::Mixed(now, spare) => run_records(core, now, spare, end, target, pause),
        }
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
        length: 0.0,
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

fn fill<const D: usize, R: Record<D>>(s: &mut System<D>, records: &[R], species: &Species) {
    for r in records {
        s.velocities.push(*r.velocity());
        s.radii.push(species.radii[r.species()]);
        s.masses.push(species.masses[r.species()]);
    }
}

fn run_records<const D: usize, R: Record<D>>(
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
                core.time = end;
            }
            return;
        }
        let next_recompute = (core.tally.collisions / n + 1) * n;
        let window = Window {
            start: core.time,
            end,
            max_collisions: target.min(next_recompute) - core.tally.collisions,
        };
        let collider = Collider {
            law: core.law.as_ref(),
            species: &core.species,
        };
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
        core.time = collider.run_classes(
            records,
            &mut core.class,
            classes,
            &core.reference,
            pair_rate,
            window,
            &mut core.stream,
            &mut core.tally,
        );
        core.speed_bound = classes.bound();
        if core.tally.collisions == next_recompute {
            let moments = Moments::of(records, &core.species);
            core.reference = moments.mean();
            core.temperature = moments.spread / (n as usize * D) as f64;
            core.speed_bound = kernel::speed_bound(records, &core.reference);
            core.classes = None;
        }
    }
}

/// How N particles split into blocks: `count` blocks, the first `longer` of them with
/// `size + 1` particles, the rest with `size`.
#[derive(Debug, Clone, Copy)]
struct Blocks {
    count: usize,
    size: usize,
    longer: usize,
}

impl Blocks {
    fn new(n: usize, block_size: usize) -> Self {
        let count = ((n as f64 / block_size as f64).round() as usize).clamp(1, n / 2);
        Blocks {
            count,
            size: n / count,
            longer: n % count,
        }
    }

    fn start(&self, b: usize) -> usize {
        b * self.size + b.min(self.longer)
    }

    fn len(&self, b: usize) -> usize {
        self.size + (b < self.longer) as usize
    }

    /// Whole lanes every block has.
    fn lanes(&self) -> usize {
        self.size / LANE
    }

    fn split<'a, T>(&self, mut data: &'a mut [T]) -> Vec<&'a mut [T]> {
        let mut parts = Vec::with_capacity(self.count);
        for b in 0..self.count {
            let (head, tail) = data.split_at_mut(self.len(b));
            parts.push(head);
            data = tail;
        }
        parts
    }
}

/// The block scheme: steps until the time reaches `end` or the collisions `target`.
#[allow(clippy::too_many_arguments)]
fn run_blocks<const D: usize, R: Record<D>>(
    core: &mut Core<D>,
    now: &mut Vec<R>,
    spare: &mut Vec<R>,
    block_size: usize,
    step: StepSize,
    end: f64,
    target: u64,
    pause: u64,
) {
    let n = now.len();
    let layout = Blocks::new(n, block_size);
    while core.tally.collisions < target.min(pause) && core.time < end {
        let omega =
            frequency_estimate::<D>(&core.species, n as f64 - 1.0, core.volume, core.temperature);
        if !positive(omega) {
            // At rest: no collision ever.
            if end.is_finite() {
                core.time = end;
            }
            return;
        }
        let mut dt = match step {
            StepSize::Auto => DEFAULT_BLOCK_COLLISIONS_PER_STEP / omega,
            StepSize::CollisionsPerParticle(x) => x / omega,
            StepSize::Fixed(dt) => dt,
        };
        if target != u64::MAX {
            // Expected collisions in dt: N omega dt / 2.
            let remaining = (target - core.tally.collisions) as f64;
            dt = dt.min(2.0 * remaining / (n as f64 * omega));
        }
        let last = dt >= end - core.time;
        if last {
            dt = end - core.time;
        }
        let (tally, mean, spread) = block_step(core, now, spare, &layout, dt);
        std::mem::swap(now, spare);
        core.tally.add(&tally);
        core.reference = mean;
        core.temperature = spread / (n * D) as f64;
        core.steps += 1;
        core.time = if last { end } else { core.time + dt };
    }
}

/// One step: every destination block gathers its particles (lane c from block
/// b + offset_c) and their speed bound about the reference velocity (the gas's mean at the
/// end of the last step), runs the exact process for `dt` with the kernel's single
/// majorant (speed classes halve the candidates here but cost twice the time: the blocks are
/// small and re-sorted every step; docs/performance.md), shuffles itself and sums its
/// mass, momentum and m |v - reference|^2. Returns the tally, the mean velocity and the
/// spread (sum of m |v - <v>|^2) of the gas.
fn block_step<const D: usize, R: Record<D>>(
    core: &Core<D>,
    now: &[R],
    spare: &mut Vec<R>,
    layout: &Blocks,
    dt: f64,
) -> (Counters, Vector<D>, f64) {
    let n = now.len();
    if spare.len() != n {
        spare.clear();
        spare.extend_from_slice(now);
    }
    let mut mixing = Stream::new(core.seed, Purpose::Mixing, core.steps, 0);
    let offsets: Vec<usize> = (0..layout.lanes())
        .map(|_| mixing.below(layout.count as u64) as usize)
        .collect();
    let collider = Collider {
        law: core.law.as_ref(),
        species: &core.species,
    };
    let (seed, steps, species) = (core.seed, core.steps, &core.species);
    let reference = core.reference;
    let base_rate =
        theory::cross_section_factor::<D>() * core.species.max_weight * (n as f64 - 1.0)
            / core.volume;
    let results: Vec<(Counters, Moments<D>)> = layout
        .split(spare)
        .into_par_iter()
        .enumerate()
        .map(|(b, block)| {
            let mut bound = gather(now, layout, &offsets, b, block, &reference).sqrt();
            let mut rng = Stream::new(seed, Purpose::Block, steps, b as u64);
            let mut tally = Counters::default();
            // Pair rate over a volume V (B - 1)/(N - 1): each particle's frequency is the gas's.
            let pair_rate = base_rate / (block.len() as f64 - 1.0);
            collider.run_for(
                block,
                &reference,
                pair_rate,
                (0.0, dt),
                &mut bound,
                &mut rng,
                &mut tally,
            );
            kernel::shuffle(block, &mut rng);
            (tally, kernel::sums_about(block, species, &reference))
        })
        .collect();
    let mut tally = Counters::default();
    for (t, _) in &results {
        tally.add(t);
    }
    let sums: Vec<Moments<D>> = results.iter().map(|r| r.1).collect();
    let (mean, spread) = kernel::pooled_about(&sums, &reference);
    (tally, mean, spread)
}

/// Lanes ahead of the one being copied whose source [`gather`] asks the processor for.
const PREFETCH_LANES: usize = 4;

/// Asks the processor to bring every cache line of `records` into cache (a hint: results
/// never depend on it).
#[inline(always)]
fn prefetch<R>(records: &[R]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let base = records.as_ptr().cast::<i8>();
        let bytes = std::mem::size_of_val(records);
        let mut offset = 0;
        while offset < bytes {
            // SAFETY: prefetching is a hint that never faults; every address lies in
            // `records`.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(base.add(offset)) };
            offset += 64;
        }
        if bytes > 0 {
            // SAFETY: as above; the last byte of `records`.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(base.add(bytes - 1)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = records;
}

/// Copies a lane as a fixed-size array (inline moves rather than a call to memmove).
#[inline(always)]
fn copy_lane<R: Copy>(from: &[R], to: &mut [R]) {
    let from: &[R; LANE] = from.try_into().expect("a lane");
    let to: &mut [R; LANE] = to.try_into().expect("a lane");
    *to = *from;
}

/// Fills destination block `b`: lane c (particles c LANE .. (c+1) LANE) from block
/// (b + offsets[c]) mod count, the rest of the block (fewer than LANE + 1) from block b.
/// Returns the largest |v - reference|^2 in the block.
fn gather<const D: usize, R: Record<D>>(
    now: &[R],
    layout: &Blocks,
    offsets: &[usize],
    b: usize,
    block: &mut [R],
    reference: &Vector<D>,
) -> f64 {
    let mut largest: f64 = 0.0;
    let mut note = |lane: &[R]| {
        for r in lane {
            let d: Vector<D> = std::array::from_fn(|k| r.velocity()[k] - reference[k]);
            largest = largest.max(dot(&d, &d));
        }
    };
    let source_of = |c: usize| layout.start((b + offsets[c]) % layout.count) + c * LANE;
    for c in 0..offsets.len() {
        // The lanes come from all over the records: ask for one a few lanes ahead.
        if c + PREFETCH_LANES < offsets.len() {
            let ahead = source_of(c + PREFETCH_LANES);
            prefetch(&now[ahead..ahead + LANE]);
        }
        let source = source_of(c);
        let lane = &mut block[c * LANE..(c + 1) * LANE];
        copy_lane(&now[source..source + LANE], lane);
        note(lane);
    }
    let done = offsets.len() * LANE;
    let (own, len) = (layout.start(b), block.len());
    block[done..].copy_from_slice(&now[own + done..own + len]);
    note(&block[done..]);
    largest
}
