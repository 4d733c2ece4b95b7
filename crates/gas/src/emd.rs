//! Event-driven molecular dynamics of smooth inelastic hard spheres.
//!
//! Particles stream freely between events; each particle stores only its earliest
//! predicted event (a collision or leaving its cell) in an indexed heap, and positions are
//! updated lazily (each particle knows the time at which its stored position is valid).
//! A predicted collision carries the partner's collision count at prediction time; it is
//! stale if the partner has collided since and is then re-predicted (Marín, Risso & Cordero
//! 1993). At each collision eps comes from the `Restitution` law with the normal impact
//! speed.

use crate::cells::{Grid, NONE};
use crate::engine::Counters;
use crate::error::{Error, Result};
use crate::shear::Virial;
use crate::sorter::{Sorter, SorterKind};
use crate::system::{dot, wrap, System, Vector};
use crate::walls::{Side, Walls, WallsState};
use restitution::Restitution;

mod driving;
mod gravity;
mod lees_edwards;
mod models;
mod predict;
mod rough;
mod state;
mod tracking;

use gravity::Field;
pub use models::BathState;
use models::{Baths, TcModel};
pub use state::{EventDrivenState, TcState};

/// Everything the engine keeps per particle, in two cache lines (D = 3). The first line
/// is all a neighbour scan reads about a neighbour: position at `valid_at`, velocity,
/// collision count and the link to the next particle of its cell. The second holds the
/// particle's own predictions (earliest collision, with the partner's collision count at
/// prediction time; the moment it leaves its cell) and its place in the cell lists.
/// Keeping both predictions lets a cell crossing look only at the new layer of cells.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(128))]
struct Particle<const D: usize> {
    /// Position in [0, L)^D at time `valid_at`.
    position: Vector<D>,
    velocity: Vector<D>,
    valid_at: f64,
    /// Collisions so far, modulo 2^32 (a prediction is stale once the partner's changes).
    count: u32,
    /// Next particle in the same cell ([`NONE`] at the end).
    next_in_cell: u32,
    collision: f64,
    crossing: f64,
    partner: u32,
    partner_count: u32,
    prev_in_cell: u32,
    cell: [u32; D],
    /// Dimension and direction of the predicted cell crossing; a dimension k + D stands
    /// for the contact with the wall on that side of axis k.
    exit_dim: u8,
    exit_up: bool,
    /// Contacts with walls, modulo 2^32: `count` advances with them too (a wall changes
    /// the velocity, so predictions with this particle go stale), and the collisions are
    /// `count - wall_hits`.
    wall_hits: u32,
    radius: f64,
    mass: f64,
}

impl<const D: usize> Particle<D> {
    #[inline]
    fn position_at(&self, t: f64) -> Vector<D> {
        let dt = t - self.valid_at;
        std::array::from_fn(|k| self.position[k] + self.velocity[k] * dt)
    }

    #[inline]
    fn next_event(&self) -> f64 {
        self.collision.min(self.crossing)
    }
}

/// Collisions per particle without time advancing (relative 1e-12) after which the engine
/// declares inelastic collapse and stops, instead of looping at a fixed time forever.
pub const COLLAPSE_COLLISIONS_PER_PARTICLE: u64 = 1000;

/// Particles per cell from which the neighbour scans prefetch each occupied cell's first
/// record. Below it most cells are empty, the records of the few neighbours are rarely
/// missed, and the prefetch pass only adds instructions (+13 % at phi = 0.05, cells one
/// diameter wide: 0.1 particles per cell); above it (0.57 per cell at phi = 0.3) the
/// overlapped misses win (docs/event-driven.md). The choice changes no event.
const PREFETCH_OCCUPANCY: f64 = 0.15;

/// The minimum image in the box: its sides and half sides, copied into the pair loops
/// (loaded once per scan, not once per pair).
#[derive(Debug, Clone, Copy)]
pub(crate) struct MinimumImage<const D: usize> {
    sides: Vector<D>,
    halves: Vector<D>,
}

impl<const D: usize> MinimumImage<D> {
    /// The separation b - a of two positions less than 1.5 L apart per component (see
    /// [`EventDriven::separation`]).
    #[inline(always)]
    fn separation(&self, a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
        std::array::from_fn(|k| {
            let (length, half) = (self.sides[k], self.halves[k]);
            let d = b[k] - a[k];
            if d > half {
                d - length
            } else if d < -half {
                d + length
            } else {
                d
            }
        })
    }
}

/// How a neighbour scan reduces the separation of two positions to the nearest image.
pub(crate) trait Images<const D: usize> {
    /// The separation b − a of the nearest images.
    fn separation(&self, a: &Vector<D>, b: &Vector<D>) -> Vector<D>;
}

impl<const D: usize> Images<D> for MinimumImage<D> {
    #[inline(always)]
    fn separation(&self, a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
        MinimumImage::separation(self, a, b)
    }
}

/// The nearest image of positions any number of boxes apart: under shear a sphere flies
/// with the flow, up to a L_y, and crosses cells that slide with it only at its peculiar
/// speed, so its position (brought up to date at its events) may lie boxes away along x.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AnyImage<const D: usize>(MinimumImage<D>);

impl<const D: usize> Images<D> for AnyImage<D> {
    #[inline(always)]
    fn separation(&self, a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
        let near = self.0.separation(a, b);
        std::array::from_fn(|k| {
            let (length, d) = (self.0.sides[k], near[k]);
            if d.abs() <= self.0.halves[k] {
                d
            } else {
                // (Rare: a sphere that flew boxes along x since its last event.)
                d - length * (d / length).round()
            }
        })
    }
}

/// The event-driven engine.
pub struct EventDriven<const D: usize> {
    /// The box; positions, velocities, radii and masses live in `particles` and are copied
    /// here only when [`EventDriven::system`] is called.
    system: System<D>,
    /// The box's sides and half sides (a copy the pair loops keep in registers).
    image: MinimumImage<D>,
    particles: Vec<Particle<D>>,
    /// The contact distance if all spheres have the same radius (no radius lookups).
    uniform_sigma: Option<f64>,
    law: Box<dyn Restitution>,
    /// A pairwise law's table and each particle's kind in it (mixtures whose pairs collide
    /// with different laws).
    pairs: Option<(restitution::pairwise::Pairwise, Vec<u16>)>,
    time: f64,
    queue: Sorter,
    /// The smallest cell width asked for (see [`EventDriven::with_cell_width`]).
    min_cell_width: f64,
    grid: Grid<D>,
    /// First particle of each cell.
    heads: Vec<u32>,
    /// One bit per cell: set if the cell holds a particle. In a dilute gas most cells are
    /// empty, and this bitmap (N/8 bytes or less) stays in cache where `heads` would not.
    occupied: Vec<u64>,
    /// Whether the neighbour scans prefetch the first record of each occupied cell
    /// ([`PREFETCH_OCCUPANCY`]).
    prefetch_scans: bool,
    tally: Counters,
    tc: Option<TcModel>,
    /// Per-particle bath temperatures, present iff the law is stochastic.
    baths: Option<Baths>,
    /// Time at which the current run of collisions without time advancing began, and
    /// their number (see [`COLLAPSE_COLLISIONS_PER_PARTICLE`]).
    stall: (f64, u64),
    /// The same for the other events (cell crossings, wall contacts): a clock that no
    /// longer resolves the events (times beyond ~1e16 mean free times) or a sphere
    /// trapped against a wall would loop without colliding. Not saved: it only ever
    /// stops a run that does not advance.
    idle: (f64, u64),
    collapsed: Option<f64>,
    /// Driving applied at discrete times ([`EventDriven::set_driving`]).
    kicks: Option<driving::Kicks>,
    /// The walls of a closed container ([`EventDriven::set_walls`]); None: periodic.
    walls: Option<Walls<D>>,
    /// Walls' state from a check-point, taken up by the next [`EventDriven::set_walls`].
    saved_walls: Option<WallsState>,
    /// Gravity ([`EventDriven::set_gravity`]); with it, particles' positions and
    /// velocities are kept in the falling frame (module `gravity`).
    field: Option<Field<D>>,
    /// Lees–Edwards boundaries ([`EventDriven::set_shear`]); None: periodic.
    shear: Option<lees_edwards::LeesEdwards>,
    /// The tensor virial, if asked for ([`EventDriven::set_virial_tensor`]).
    virial: Option<Virial>,
    /// The particles' tracks, if asked for ([`EventDriven::set_tracking`]).
    tracks: Option<crate::tail::Tracks>,
    /// The law's tangential rule (rough spheres; module `rough`).
    tangential: Option<restitution::rough::Tangential>,
    /// A rule per pair of kinds and each particle's kind in it (mixtures whose pairs
    /// differ in roughness).
    tangential_pairs: Option<(restitution::rough::TangentialPairs, Vec<u16>)>,
    /// The spheres' rotation ([`EventDriven::set_rotation`]; present with a rough law).
    rotation: Option<crate::rotation::Rotation>,
}

impl<const D: usize> EventDriven<D> {
    /// An engine at time 0 with cells one diameter wide; fails if spheres overlap.
    pub fn new(system: System<D>, law: Box<dyn Restitution>) -> Result<Self> {
        Self::with_cell_width(system, law, 0.0)
    }

    /// As [`EventDriven::new`] with cells at least `min_width` wide (and at least one
    /// diameter). At least 4 cells per side are required: then two particles in adjacent
    /// cells are closer than L/2 in every direction, so the minimum image used to predict
    /// their collision is the image that collides. (With fewer cells, or all pairs, a
    /// prediction far ahead can pick the wrong periodic image and miss a collision.)
    pub fn with_cell_width(
        system: System<D>,
        law: Box<dyn Restitution>,
        min_width: f64,
    ) -> Result<Self> {
        let mut engine = Self::assemble(system, law, min_width, None, 0.0)?;
        engine.predict_all();
        Ok(engine)
    }

    /// The engine at time `time` with its particles (all valid then) in the cell lists and
    /// nothing predicted, sheared by `shear` (its lab velocities as given); fails if
    /// spheres overlap.
    fn assemble(
        mut system: System<D>,
        law: Box<dyn Restitution>,
        min_width: f64,
        shear: Option<crate::shear::Shear>,
        time: f64,
    ) -> Result<Self> {
        let n = system.len();
        if system.velocities.len() != n || system.radii.len() != n || system.masses.len() != n {
            return Err(Error::LengthMismatch {
                what: "positions, velocities, radii and masses".into(),
            });
        }
        let max_diameter = 2.0 * system.radii.iter().cloned().fold(0.0, f64::max);
        if max_diameter <= 0.0 {
            return Err(Error::out_of_range("radii", "all 0", "a positive radius"));
        }
        let grid = Grid::new(
            &system.sides,
            max_diameter.max(min_width),
            crate::cells::max_cells(n),
        );
        if grid.fewest_per_side() < 4 {
            return Err(Error::BoxTooSmall {
                length: system.shortest_side(),
                width: max_diameter.max(min_width),
            });
        }
        let sides = system.sides;
        let particles: Vec<Particle<D>> = system
            .positions
            .iter()
            .zip(&system.velocities)
            .zip(system.radii.iter().zip(&system.masses))
            .map(|((p, v), (&radius, &mass))| Particle {
                position: std::array::from_fn(|k| wrap(p[k], sides[k])),
                velocity: *v,
                valid_at: 0.0,
                count: 0,
                next_in_cell: NONE,
                collision: f64::INFINITY,
                crossing: f64::INFINITY,
                partner: NONE,
                partner_count: 0,
                prev_in_cell: NONE,
                cell: [0; D],
                exit_dim: 0,
                exit_up: false,
                wall_hits: 0,
                radius,
                mass,
            })
            .collect();
        let radius = system.radii[0];
        let uniform_sigma = system
            .radii
            .iter()
            .all(|&r| r == radius)
            .then_some(2.0 * radius);
        // The engine's copy is the only one while it runs (see `system()`).
        system.positions = Vec::new();
        system.velocities = Vec::new();
        system.radii = Vec::new();
        system.masses = Vec::new();
        let law_is_stochastic = law.stochastic().is_some();
        let pairs = match law.pairwise() {
            None => None,
            Some(_) if law_is_stochastic => {
                return Err(Error::out_of_range(
                    "restitution",
                    "stochastic and pairwise",
                    "one of them",
                ))
            }
            Some(table) => {
                let kinds = particles
                    .iter()
                    .map(|p| {
                        table
                            .kind_of(p.radius, p.mass)
                            .map(|k| k as u16)
                            .ok_or_else(|| {
                                Error::out_of_range(
                                    "restitution",
                                    format!(
                                        "no law for particles of radius {} and mass {}",
                                        p.radius, p.mass
                                    ),
                                    "a law for every pair of species",
                                )
                            })
                    })
                    .collect::<Result<Vec<u16>>>()?;
                Some((table.clone(), kinds))
            }
        };
        let mut engine = EventDriven {
            image: MinimumImage {
                sides: system.sides,
                halves: system.sides.map(|l| 0.5 * l),
            },
            system,
            particles,
            uniform_sigma,
            law,
            pairs,
            time: 0.0,
            queue: Sorter::new(SorterKind::default(), n),
            min_cell_width: min_width,
            grid,
            heads: vec![NONE; grid.cells()],
            occupied: vec![0; grid.cells().div_ceil(64)],
            prefetch_scans: n as f64 >= PREFETCH_OCCUPANCY * grid.cells() as f64,
            tally: Counters::default(),
            tc: None,
            baths: law_is_stochastic.then(|| Baths::new(vec![0.0; n], 0)),
            stall: (0.0, 0),
            idle: (0.0, 0),
            collapsed: None,
            kicks: None,
            walls: None,
            saved_walls: None,
            field: None,
            shear: None,
            virial: None,
            tracks: None,
            tangential: None,
            tangential_pairs: None,
            rotation: None,
        };
        // Rough spheres start as solid spheres at rest until given their rotation.
        engine.tangential = engine.law.tangential().copied();
        engine.tangential_pairs = rough::kinds_of(engine.law.as_ref(), &engine.particles)?;
        if engine.tangential.is_some() {
            engine.rotation = Some(crate::rotation::Rotation::at_rest(n, 0.4));
        }
        engine.time = time;
        for p in &mut engine.particles {
            p.valid_at = time;
        }
        engine.shear = shear.map(|s| engine.lees_edwards(s));
        for i in 0..n {
            let c = engine.cell_of(&engine.particles[i].position);
            engine.insert(i, c);
        }
        engine.check_overlaps()?;
        Ok(engine)
    }

    /// Fails, naming the first pair (in the particle order), if two spheres overlap (the
    /// scan runs in parallel; it only reads).
    fn check_overlaps(&self) -> Result<()> {
        use rayon::prelude::*;
        let first = (0..self.particles.len())
            .into_par_iter()
            .find_map_first(|i| {
                let mut overlap = None;
                let (pi, vi) = self.now(i);
                let mut check = |p: &Vector<D>, j: usize| {
                    if j > i {
                        let r = self.separation(p, &self.particles[j].position_at(self.time));
                        let sigma = self.sigma(i, j);
                        if dot(&r, &r) < sigma * sigma * (1.0 - 1e-12) {
                            overlap = Some(j);
                        }
                    }
                };
                if self.shear.is_some() {
                    self.for_each_sheared_neighbor(i, &pi, &vi, |p, _, j| check(p, j));
                } else {
                    self.for_each_neighbor(i, |j| check(&pi, j));
                }
                overlap.map(|j| (i, j))
            });
        match first {
            Some((i, j)) => Err(Error::Overlap(i, j)),
            None => Ok(()),
        }
    }

    /// Switches the sorter (the events stay the same).
    pub fn set_sorter(&mut self, kind: SorterKind) {
        let mut queue = Sorter::new(kind, self.particles.len());
        for (i, p) in self.particles.iter().enumerate() {
            queue.update(i, p.next_event());
        }
        self.queue = queue;
    }

    /// Whether the neighbour scans prefetch (chosen by the particles per cell,
    /// [`PREFETCH_OCCUPANCY`]), and the particles per cell it was chosen by.
    pub fn neighbour_prefetch(&self) -> (bool, f64) {
        (
            self.prefetch_scans,
            self.particles.len() as f64 / self.grid.cells() as f64,
        )
    }

    /// The contact distance of i and j.
    #[inline]
    fn sigma(&self, i: usize, j: usize) -> f64 {
        match self.uniform_sigma {
            Some(sigma) => sigma,
            None => self.particles[i].radius + self.particles[j].radius,
        }
    }

    /// Minimum-image separation b - a of two positions less than 1.5 L apart per
    /// component (stored positions are in [0, L) and streamed less than a cell beyond).
    /// In a container the scans never pair spheres across a wall ([`Self::keep_inside`]):
    /// the pairs they see lie in adjacent cells, whose nearest image is the direct one.
    #[inline]
    fn separation(&self, a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
        self.image.separation(a, b)
    }

    #[inline]
    fn bring_to_now(&mut self, i: usize) {
        self.bring_to_now_as::<true>(i);
    }

    /// [`Self::bring_to_now`]; `EXTENDED = false` only where the engine is neither
    /// sheared nor tracked (the periodic event loop, [`Self::step_as`]).
    #[inline]
    fn bring_to_now_as<const EXTENDED: bool>(&mut self, i: usize) {
        if EXTENDED && (self.shear.is_some() || self.tracks.is_some()) {
            self.bring_to_now_sheared_or_tracked(i);
            return;
        }
        let sides = self.system.sides;
        let p = &mut self.particles[i];
        let x = p.position_at(self.time);
        p.position = match &self.field {
            None => std::array::from_fn(|k| wrap(x[k], sides[k])),
            // Axes with gravity are closed: the falling frame's y is not wrapped.
            Some(f) => std::array::from_fn(|k| {
                if f.g[k] == 0.0 {
                    wrap(x[k], sides[k])
                } else {
                    x[k]
                }
            }),
        };
        p.valid_at = self.time;
    }

    /// [`Self::bring_to_now`] under shear (y is not wrapped: only a crossing of a face
    /// moves a sphere to its image, module `lees_edwards`) or with tracks (the wraps are
    /// counted). Out of line: the periodic box's path stays short enough to inline.
    #[inline(never)]
    fn bring_to_now_sheared_or_tracked(&mut self, i: usize) {
        let sides = self.system.sides;
        let sheared = self.shear.is_some();
        let p = &mut self.particles[i];
        let x = p.position_at(self.time);
        p.position = match &self.field {
            None => std::array::from_fn(|k| {
                if sheared && k == 1 {
                    x[k]
                } else {
                    wrap(x[k], sides[k])
                }
            }),
            Some(f) => std::array::from_fn(|k| {
                if f.g[k] == 0.0 {
                    wrap(x[k], sides[k])
                } else {
                    x[k]
                }
            }),
        };
        p.valid_at = self.time;
        if let Some(tracks) = self.tracks.as_mut() {
            let wrapped = self.particles[i].position;
            for k in 0..D {
                if x[k] != wrapped[k] {
                    tracks.note_wrap::<D>(i, k, x[k], wrapped[k], sides[k]);
                }
            }
        }
    }

    /// A pair whose next collision is earlier than both particles' scheduled events
    /// (which the sorter must never allow), with that collision time. O(N^2): for tests.
    pub fn missed_collision(&self) -> Option<(usize, usize, f64)> {
        let n = self.particles.len();
        for i in 0..n {
            let (pi, vi) = self.now(i);
            for j in i + 1..n {
                if self.across_a_wall(&pi, &self.particles[j].position_at(self.time)) {
                    continue;
                }
                if self.shear.is_some() {
                    if let Some(t) = self.missed_across(i, j) {
                        return Some((i, j, t));
                    }
                    continue;
                }
                if let Some(dt) = self.collision_delay(&pi, &vi, j, self.sigma(i, j), &self.image) {
                    let t = self.time + dt;
                    let scheduled = self.queue.time_of(i).min(self.queue.time_of(j));
                    if t < scheduled * (1.0 - 1e-12) - 1e-12 {
                        return Some((i, j, t));
                    }
                }
            }
        }
        None
    }

    /// Whether the nearest image of b seen from a lies across a wall (then the two never
    /// meet there).
    fn across_a_wall(&self, a: &Vector<D>, b: &Vector<D>) -> bool {
        let sides = &self.system.sides;
        self.walls
            .as_ref()
            .is_some_and(|w| (0..D).any(|k| w.closed(k) && (b[k] - a[k]).abs() > 0.5 * sides[k]))
    }

    /// Processes the next event; false if there is none (all particles at rest).
    pub fn step(&mut self) -> bool {
        if self.shear.is_some()
            || self.tracks.is_some()
            || self.virial.is_some()
            || self.rotation.is_some()
        {
            self.step_extended()
        } else {
            self.step_as::<false>()
        }
    }

    /// [`Self::step`] with shear, tracks, the tensor virial or rotation, out of line: the periodic
    /// loop's code stays as small as it was (the compiler inlines into it as before).
    #[inline(never)]
    fn step_extended(&mut self) -> bool {
        self.step_as::<true>()
    }

    /// [`Self::step`], compiled twice: with `EXTENDED = false` (neither shear, tracks
    /// nor the tensor virial) the periodic gas's loop has none of their checks: it
    /// costs what it cost before they existed.
    fn step_as<const EXTENDED: bool>(&mut self) -> bool {
        if self.collapsed.is_some() {
            return false;
        }
        let next_event = self.queue.peek();
        if let Some(shift) = self.next_shift().filter(|_| EXTENDED) {
            let first = self.next_kick().is_none_or(|kick| shift < kick);
            if first && next_event.is_none_or(|(_, t)| shift <= t) {
                self.shift();
                return true;
            }
        }
        if let Some(kick) = self.next_kick() {
            if next_event.is_none_or(|(_, t)| kick <= t) {
                self.kick();
                return true;
            }
        }
        let Some((i, t)) = next_event else {
            return false;
        };
        if !t.is_finite() {
            return false;
        }
        self.time = t;
        self.tally.events += 1;
        if let Some(k) = self.queue.runner_up() {
            // Its record is usually needed by the next step: fetch it while this one runs.
            prefetch(&self.particles[k]);
        }
        let next = self.particles[i];
        if next.crossing <= next.collision {
            self.watch_for_idling();
            let (dim, up) = (next.exit_dim as usize, next.exit_up);
            if dim >= D {
                self.hit_wall(i, dim - D, up);
                self.predict_as::<EXTENDED>(i);
            } else if EXTENDED && dim == 1 && self.shear.is_some() {
                self.cross_row(i, up);
            } else {
                self.bring_to_now_as::<EXTENDED>(i);
                self.remove(i);
                self.insert(i, self.grid.shifted(&next.cell, dim, up));
                self.predict_after_crossing_as::<EXTENDED>(i, dim, up);
            }
        } else {
            let j = next.partner as usize;
            if self.particles[j].count == next.partner_count {
                self.collide_as::<EXTENDED>(i, j);
                self.predict_as::<EXTENDED>(i);
                self.predict_as::<EXTENDED>(j);
            } else {
                self.predict_as::<EXTENDED>(i);
            }
        }
        true
    }

    /// The collision of i and j at the current time (`EXTENDED`: as in [`Self::step_as`]).
    fn collide_as<const EXTENDED: bool>(&mut self, i: usize, j: usize) {
        // Across a sheared face the image of the second sphere is computed (with its
        // rounding): the pair in one order, whichever of the two the sorter gives first
        // among equal times, so that a restored engine collides it with the same bits.
        let (i, j) = if EXTENDED && self.shear.is_some() && j < i {
            (j, i)
        } else {
            (i, j)
        };
        self.bring_to_now_as::<EXTENDED>(i);
        self.bring_to_now_as::<EXTENDED>(j);
        let (a, b) = (self.particles[i], self.particles[j]);
        let (r, jump) = match self.shear.as_ref().filter(|_| EXTENDED) {
            None => (self.separation(&a.position, &b.position), 0.0),
            Some(_) => self.sheared_separation(&a, &b),
        };
        let distance = dot(&r, &r).sqrt();
        let n: Vector<D> = std::array::from_fn(|k| r[k] / distance);
        let mut approach = -(0..D)
            .map(|k| (b.velocity[k] - a.velocity[k]) * n[k])
            .sum::<f64>();
        if EXTENDED && jump != 0.0 {
            // b's image across a sheared face moves with b's velocity + jump e_x.
            approach -= jump * n[0];
        }
        let (mi, mj) = (a.mass, b.mass);
        let reduced = mi * mj / (mi + mj);
        let mut elastic = false;
        if let Some(tc) = &mut self.tc {
            if self.time - tc.last[i] < tc.duration || self.time - tc.last[j] < tc.duration {
                elastic = true;
                self.tally.tc_elastic += 1;
            }
            tc.last[i] = self.time;
            tc.last[j] = self.time;
        }
        let (impulse, lost) = if elastic {
            (2.0 * reduced * approach, 0.0)
        } else {
            self.impulse(i, j, reduced, approach)
        };
        let (pa, pb) = (&mut self.particles[i], impulse / mi);
        for (k, nk) in n.iter().enumerate() {
            pa.velocity[k] -= pb * nk;
        }
        pa.count = pa.count.wrapping_add(1);
        let pj = &mut self.particles[j];
        for (k, nk) in n.iter().enumerate() {
            pj.velocity[k] += impulse / mj * nk;
        }
        pj.count = pj.count.wrapping_add(1);
        self.tally.collisions += 1;
        self.watch_for_collapse();
        self.tally.energy_lost += lost;
        self.tally.virial += impulse * distance;
        if EXTENDED {
            if let Some(virial) = &mut self.virial {
                virial.add(impulse, distance, &n);
            }
            if !elastic && self.tangential.is_some() {
                self.rough_kick((i, j), &n, distance, impulse, jump);
            }
        }
    }

    /// The contact of i with the wall on the high (`up`) or low side of axis k, now.
    fn hit_wall(&mut self, i: usize, k: usize, up: bool) {
        self.keep_frame_near();
        self.bring_to_now(i);
        let side = if up { Side::High } else { Side::Low };
        let Some(walls) = self.walls.as_mut() else {
            return;
        };
        let Some(index) = walls.at(k, side) else {
            return;
        };
        let p = &mut self.particles[i];
        let touched = match &self.field {
            None => walls.bounce(index, p.mass, &mut p.velocity, self.time),
            Some(f) => {
                // The wall acts on the velocity in the box.
                let (x, mut v) = f.to_box(&p.position, &p.velocity, self.time);
                let touched = walls.bounce(index, p.mass, &mut v, self.time);
                p.velocity = f.to_falling(&x, &v, self.time).1;
                touched
            }
        };
        if !touched {
            // A vibrating wall's early check: the velocity is unchanged.
            return;
        }
        p.count = p.count.wrapping_add(1);
        p.wall_hits = p.wall_hits.wrapping_add(1);
    }

    /// Puts the gas into a container with `walls` (None: periodic again) and predicts
    /// every event anew. Fails if a sphere is not inside the walls (its centre at least
    /// its radius from each). Takes up the walls' tallies from a restored check-point
    /// (then the walls must be as many).
    pub fn set_walls(&mut self, walls: Option<Walls<D>>) -> Result<()> {
        let mut walls = walls;
        if let Some(w) = walls.as_mut() {
            let sides = self.system.sides;
            let largest = self.particles.iter().map(|p| p.radius).fold(0.0, f64::max);
            w.check_sweeps(&sides, 2.0 * largest)?;
            for i in 0..self.particles.len() {
                let (x, _) = self.in_box_now(i);
                let p = &self.particles[i];
                for k in (0..D).filter(|&k| w.closed(k)) {
                    let length = sides[k];
                    // A vibrating wall is displaced d(t) into the box.
                    let (low, high) = (
                        w.displacement(k, Side::Low, self.time),
                        w.displacement(k, Side::High, self.time),
                    );
                    if x[k] < low + p.radius || x[k] > length - high - p.radius {
                        return Err(Error::out_of_range(
                            "wall",
                            format!("sphere {i} at {} on axis {k}, radius {}", x[k], p.radius),
                            format!(
                                "spheres inside the walls ({} .. {})",
                                p.radius,
                                length - p.radius
                            ),
                        ));
                    }
                }
            }
        }
        crate::walls::take_up(walls.as_mut(), self.saved_walls.take())?;
        self.walls = walls;
        self.synchronize();
        Ok(())
    }

    /// The walls, if the gas is in a container.
    pub fn walls(&self) -> Option<&Walls<D>> {
        self.walls.as_ref()
    }

    /// Counts collisions at a standing time; declares collapse after too many.
    fn watch_for_collapse(&mut self) {
        let (since, count) = self.stall;
        if self.time > since + 1e-12 * since.abs() {
            self.stall = (self.time, 0);
        } else if count + 1 >= COLLAPSE_COLLISIONS_PER_PARTICLE * self.particles.len() as u64 {
            self.collapsed = Some(self.time);
        } else {
            self.stall.1 = count + 1;
        }
    }

    /// Counts crossings and wall contacts at a standing time; declares collapse (the run
    /// stops there) after as many per particle as [`Self::watch_for_collapse`] allows.
    fn watch_for_idling(&mut self) {
        let (since, count) = self.idle;
        if self.time > since + 1e-12 * since.abs() {
            self.idle = (self.time, 0);
        } else if count + 1 >= COLLAPSE_COLLISIONS_PER_PARTICLE * self.particles.len() as u64 {
            self.collapsed = Some(self.time);
        } else {
            self.idle.1 = count + 1;
        }
    }

    /// The time of the next event or application of the driving, whichever first.
    fn upcoming(&mut self) -> Option<f64> {
        let event = self.queue.peek().map(|(_, t)| t);
        let first = match (event, self.next_kick()) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        match (first, self.next_shift()) {
            // A shift alone is no reason to go on: nothing moves.
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, _) => a,
        }
    }

    /// Sums the tensor virial of the collisions from now on (`true`, from zero unless it
    /// is summed already) or stops (`false`).
    pub fn set_virial_tensor(&mut self, on: bool) {
        if !on {
            self.virial = None;
        } else if self.virial.is_none() {
            self.virial = Some(Virial::default());
        }
    }

    /// Runs until the time reaches `end` or the collision tally reaches `collisions`,
    /// whichever first. Particles are brought to the present lazily, so stopping after a
    /// collision and going on changes nothing (see [`crate::Engine::run_paused`]).
    pub fn run_bounded(&mut self, end: f64, collisions: u64) {
        while self.tally.collisions < collisions {
            match self.upcoming() {
                Some(next) if next <= end => {
                    if !self.step() {
                        return;
                    }
                }
                _ => {
                    // Nothing left before `end`: the time reaches it (as in run_until).
                    if self.collapsed.is_none() && end.is_finite() {
                        self.time = self.time.max(end);
                    }
                    return;
                }
            }
        }
    }
}

/// Asks the processor to bring both cache lines of a particle record into cache.
#[inline]
fn prefetch<const D: usize>(p: &Particle<D>) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let base = (p as *const Particle<D>).cast::<i8>();
        // SAFETY: prefetching is a hint that never faults; both addresses lie in `p`.
        unsafe {
            _mm_prefetch::<_MM_HINT_T0>(base);
            _mm_prefetch::<_MM_HINT_T0>(base.add(64));
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

/// Asks the CPU for the first cache line of particle record `p` (all a neighbour scan
/// reads of it), without waiting for it.
#[inline]
fn prefetch_first_line<const D: usize>(p: &Particle<D>) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: prefetching is a hint that never faults; the address lies in `p`.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((p as *const Particle<D>).cast::<i8>()) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The record of a 3D particle is two cache lines, the neighbour data the first.
    #[test]
    fn particle_record_is_two_cache_lines() {
        assert_eq!(std::mem::size_of::<Particle<3>>(), 128);
        assert_eq!(std::mem::offset_of!(Particle<3>, next_in_cell), 60);
    }
}
