//! The spatially resolved DSMC engine: free streaming in a periodic box, then the exact
//! majorant process inside each collision cell.

use super::cell_sort::CellSorter;
use super::domain::{Slabs, Traffic};
use super::kernel::{Moments, Simulator};
use super::rough::Spin;
use super::species::Species;
use super::{check_input, frequency_estimate, positive, SpatialSnapshot, StepSize};
use crate::engine::Counters;
use crate::error::{require_positive, Error, Result};
use crate::parallel::{Communicator, Local};
use crate::system::{wrap, System, Vector};
use crate::theory;
use restitution::Restitution;
use std::sync::Arc;

mod container;
mod engine;
mod flow;
mod ranks;
pub(super) mod record;
mod rough;
mod step;
mod sums;
mod tracking;
use record::Records;
use step::{cell_index, cell_key};

/// Collision cell width in mean free paths when none is given.
pub const DEFAULT_CELL_WIDTH_IN_MEAN_FREE_PATHS: f64 = 0.5;

/// Simulated particles per cell (on average) that the default cell width keeps at least.
pub const DEFAULT_MIN_PARTICLES_PER_CELL: f64 = 10.0;

/// Options of [`SpatialDsmc`].
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpatialOptions {
    /// Width of the collision cells, widened to the nearest width that divides the box
    /// side. None: [`DEFAULT_CELL_WIDTH_IN_MEAN_FREE_PATHS`] mean free paths
    /// 1 / (sqrt 2 n c_D g2 sigma^(D-1)) (Bird 1994, Sec. 11.1: cells of a fraction of the mean
    /// free path), widened where needed to hold [`DEFAULT_MIN_PARTICLES_PER_CELL`] simulated
    /// particles on average.
    ///
    /// Few particles per cell make the same pairs collide again and again, which biases the
    /// cooling: with F = 1 at phi = 0.1 (3D, eps = 0.9), T / T_Haff after 4 Haff times was
    /// 3.5 at 0.02 particles per cell (half a mean free path), 1.10 at 1.4, 1.024 at 12 and
    /// 20, 1.013 at 39 (cells of 0.5 to 6 mean free paths); with F = 0.006 and 30 particles
    /// in cells of half a mean free path, 1.006 (the homogeneous engine: 1.001). Resolving
    /// the mean free path with enough particles per cell needs F << 1: more simulated
    /// particles than physical ones (e.g. [`super::point_gas`] in a box of a few mean free
    /// paths).
    pub cell_width: Option<f64>,
    /// The time step. `StepSize::Auto`: 0.2 collisions per particle, or the time to cross
    /// half a cell at the mean speed if that is shorter.
    pub step: StepSize,
}

/// DSMC of a granular gas in a periodic box (see the [module](super) documentation).
///
/// Each step of time dt: (1) every particle streams freely, x += v dt (wrapped); (2) the
/// particles are sorted by collision cell (a stable sort: the order is unique); (3) in every
/// occupied cell, in parallel, the exact majorant process of [`super::kernel`] runs for dt among
/// the cell's n_c particles with pair rate W c_D |g| F / V_cell, where W = g2 sigma^(D-1)
/// with g2 of the mean packing fraction (the "Enskog-factor DSMC" approximation: no
/// spatial offset of the collision partners) and F = phi V_box / (sum of sphere volumes)
/// the physical particles each simulated one stands for (F = 1 for a system from
/// `init::monodisperse` at the same phi; smaller F gives more particles per cell). The
/// random impact direction is drawn as in the homogeneous engine; cell positions play no
/// part in a collision.
///
/// Errors (Bird 1994; Garcia & Wagner 2000; Hadjiconstantinou 2000): transport
/// coefficients carry O(dt^2) and O(cell width^2) errors from splitting streaming and
/// collisions; a cell of few particles re-collides the same pairs (a correlation of order
/// dt omega / n_c, which wants n_c >~ 10). Since E[n_c (n_c - 1)] = N (N - 1) (V_cell/V)^2
/// for uniformly placed particles, the mean collision rate of a homogeneous gas is exact for
/// any cell size and step.
pub struct SpatialDsmc<const D: usize> {
    /// The particles of this rank: smooth, or rough with their spins ([`record`]).
    records: Records<D>,
    species: Species,
    law: Box<dyn Restitution>,
    /// The law of each pair of species (pairwise laws; [`super::species::engine_laws`]).
    pairs: Option<Vec<Box<dyn Restitution>>>,
    options: SpatialOptions,
    phi: f64,
    seed: u64,
    /// The box's sides, and the collision cells along each axis.
    sides: Vector<D>,
    cells: [u64; D],
    /// Physical particles per simulated one.
    weight: f64,
    time: f64,
    steps: u64,
    tally: Counters,
    /// Collisions of each species' particles (mixtures; empty for one species).
    species_collisions: Vec<u64>,
    temperature: f64,
    system: System<D>,
    /// Scratch of the sort into cells.
    sorter: CellSorter,
    /// The ranks the run is spread over ([`Local`]: this process alone), the slabs of cells
    /// each owns, and the particles of all ranks.
    comm: Arc<dyn Communicator>,
    slabs: Slabs,
    total: usize,
    /// Places of the local particles in the global order, until the first step sorts them
    /// by cell (None after it, and on one rank).
    ordinals: Option<Vec<u64>>,
    traffic: Traffic,
    /// The walls of a container ([`SpatialDsmc::set_walls`]); None: periodic.
    walls: Option<crate::walls::Walls<D>>,
    /// Walls' state from a check-point, taken up by the next [`SpatialDsmc::set_walls`].
    saved_walls: Option<crate::walls::WallsState>,
    /// Gravity ([`SpatialDsmc::set_gravity`]).
    gravity: Option<Vector<D>>,
    /// Lees–Edwards boundaries ([`SpatialDsmc::set_shear`]); None: periodic.
    shear: Option<crate::shear::Shear>,
    /// The tensor virial of the collisions, if summed.
    virial: Option<crate::shear::Virial>,
    /// The displacements since tracking began, by identity ([`SpatialDsmc::set_tracking`]),
    /// and the positions after the last step they were followed to, by identity.
    tracks: Option<crate::tail::Tracks>,
    tracked_positions: Vec<Vector<D>>,
    /// Rough particles: the tangential rules, inertia factors and contacts that slid
    /// ([`rough`]); None for smooth ones.
    spin: Option<Spin>,
    /// Output buffer of the rotation (rough particles).
    rotation: Option<crate::rotation::Rotation>,
}

impl<const D: usize> SpatialDsmc<D> {
    /// An engine at time 0 from `system` (positions in the periodic box of
    /// `system.sides`, wrapped into it), the physical packing fraction `phi`
    /// (0 < phi < close packing), the law, a seed and the options. Fails, naming the
    /// parameter, for bad input.
    pub fn new(
        system: System<D>,
        phi: f64,
        law: Box<dyn Restitution>,
        seed: u64,
        options: SpatialOptions,
    ) -> Result<Self> {
        Self::distributed(system, phi, law, seed, options, Arc::new(Local))
    }

    /// The engine of [`SpatialDsmc::new`] spread over the ranks of `comm` (every rank calls
    /// this with the same arguments): each keeps the particles in its slab of collision
    /// cells ([`super::domain`]). Its run is the single process's, bit for bit, on any
    /// number of ranks. Fails for more ranks than planes of cells along the last axis
    /// (`ranks`).
    pub fn distributed(
        system: System<D>,
        phi: f64,
        law: Box<dyn Restitution>,
        seed: u64,
        options: SpatialOptions,
        comm: Arc<dyn Communicator>,
    ) -> Result<Self> {
        check_input(&system, phi)?;
        let sides = system.sides;
        for &l in &sides {
            require_positive("length", l)?;
        }
        let shortest = system.shortest_side();
        let n = system.velocities.len();
        if system.positions.len() != n {
            return Err(Error::LengthMismatch {
                what: "positions and velocities".into(),
            });
        }
        if let Some(i) = system
            .positions
            .iter()
            .position(|x| x.iter().any(|c| !c.is_finite()))
        {
            return Err(Error::NotFinite {
                what: "positions",
                index: i,
            });
        }
        options.step.check()?;
        let (species, index) = Species::of::<D>(&system.radii, &system.masses, phi)?;
        let (law, pairs) = super::species::engine_laws(law, &species)?;
        let box_volume = system.volume();
        let weight = phi * box_volume / species.sphere_volume;
        let density = n as f64 * weight / box_volume;
        let mean_free_path = 1.0
            / (2f64.sqrt() * density * theory::cross_section_factor::<D>() * species.max_weight);
        let width = match options.cell_width {
            None => {
                let crowded =
                    (DEFAULT_MIN_PARTICLES_PER_CELL * box_volume / n as f64).powf(1.0 / D as f64);
                (DEFAULT_CELL_WIDTH_IN_MEAN_FREE_PATHS * mean_free_path)
                    .max(crowded)
                    .min(shortest)
            }
            Some(w) if w.is_finite() && w > 0.0 && w <= shortest => w,
            Some(w) => {
                return Err(Error::out_of_range(
                    "cell_width",
                    w,
                    format!("0 < width <= box side {shortest}"),
                ))
            }
        };
        // The largest number of cells along each axis that are at least `width` wide.
        let per_axis: [f64; D] =
            std::array::from_fn(|k| (sides[k] / width * (1.0 + 1e-12)).floor().max(1.0));
        if per_axis.iter().product::<f64>() > (1u64 << 62) as f64 {
            return Err(Error::out_of_range(
                "cell_width",
                width,
                format!("at most 2^62 cells (box sides {sides:?})"),
            ));
        }
        let cells: [u64; D] = per_axis.map(|c| c as u64);
        let ranks = comm.size();
        if ranks as u64 > cells[D - 1] {
            return Err(Error::TooManyRanks {
                ranks,
                allowed: format!(
                    "at most {}, the planes of collision cells along the last axis (cell \
                     width {}): each rank owns whole planes",
                    cells[D - 1],
                    sides[D - 1] / cells[D - 1] as f64
                ),
            });
        }
        let mut simulators: Vec<Simulator<D>> = system
            .positions
            .iter()
            .zip(&system.velocities)
            .zip(&index)
            .enumerate()
            .map(|(i, ((x, v), &s))| Simulator {
                position: std::array::from_fn(|k| wrap(x[k], sides[k])),
                velocity: *v,
                species: s,
                id: i as u32,
            })
            .collect();
        let temperature = Moments::of(&simulators, &species).spread / (n * D) as f64;
        let width: [f64; D] = std::array::from_fn(|k| sides[k] / cells[k] as f64);
        let key = |p: &Simulator<D>| cell_key(&p.position, &width, &cells);
        let cells_per_plane = cells[..D - 1].iter().product::<u64>();
        let mut counts = vec![0u64; cells[D - 1] as usize];
        simulators
            .iter()
            .for_each(|p| counts[(key(p) / cells_per_plane) as usize] += 1);
        let slabs = Slabs::balanced(&counts, cells_per_plane, ranks);
        let mut ordinals = None;
        if ranks > 1 {
            let rank = comm.rank();
            let mine: Vec<usize> = (0..n)
                .filter(|&i| slabs.owner(key(&simulators[i]) / cells_per_plane) == rank)
                .collect();
            simulators = mine.iter().map(|&i| simulators[i]).collect();
            ordinals = Some(mine.into_iter().map(|i| i as u64).collect());
        }
        let mut engine = SpatialDsmc {
            records: Records::Smooth(simulators),
            species,
            law,
            pairs,
            options,
            phi,
            seed,
            sides,
            cells,
            weight,
            time: 0.0,
            steps: 0,
            tally: Counters::default(),
            species_collisions: Vec::new(),
            temperature,
            system: System {
                sides,
                positions: Vec::new(),
                velocities: Vec::new(),
                radii: Vec::new(),
                masses: Vec::new(),
            },
            sorter: CellSorter::default(),
            comm,
            slabs,
            total: n,
            ordinals,
            traffic: Traffic::default(),
            walls: None,
            saved_walls: None,
            gravity: None,
            shear: None,
            virial: None,
            tracks: None,
            tracked_positions: Vec::new(),
            spin: None,
            rotation: None,
        };
        engine.start_rough_at_rest();
        Ok(engine)
    }

    /// The engine of `snapshot` over the ranks of `comm` (every rank reads the same
    /// snapshot; it need not come from as many ranks): the single process's run, bit for
    /// bit. The snapshot is checked first ([`SpatialSnapshot::check`]).
    pub fn restore_distributed(
        snapshot: SpatialSnapshot<D>,
        law: Box<dyn Restitution>,
        comm: Arc<dyn Communicator>,
    ) -> Result<Self> {
        snapshot.check(true)?;
        snapshot.check_step_temperature()?;
        let mut engine = Self::distributed(
            snapshot.system,
            snapshot.packing_fraction,
            law,
            snapshot.seed,
            snapshot.options,
            comm,
        )?;
        engine.time = snapshot.time;
        engine.steps = snapshot.steps;
        engine.tally = snapshot.counters;
        engine.species_collisions = snapshot.species_collisions;
        engine.temperature = snapshot.temperature;
        if snapshot.tail.shear.is_some() && snapshot.tail.walls.is_some() {
            return Err(Error::out_of_range(
                "shear",
                "a sheared state in a container",
                "a periodic box (Lees-Edwards boundaries on x and y)",
            ));
        }
        engine.shear = snapshot.tail.shear;
        engine.virial = snapshot.tail.virial;
        engine.saved_walls = snapshot.tail.walls;
        if let Some(tracks) = snapshot.tail.tracks {
            tracks.check(D * engine.total)?;
            // Identities are the restored records' places: the order the tracks were saved in.
            engine.tracks = Some(tracks);
            engine.set_tracking(true)?;
        }
        if let Some(rotation) = snapshot.tail.rotation {
            engine.set_rotation_of(Some(rotation))?;
        }
        Ok(engine)
    }

    /// The state, step counter and options, to continue later bit for bit.
    pub fn snapshot(&mut self) -> SpatialSnapshot<D> {
        let (phi, seed, options, time, steps, tally, temperature) = (
            self.phi,
            self.seed,
            self.options,
            self.time,
            self.steps,
            self.tally,
            self.temperature,
        );
        // Lab velocities: the flow is part of the state.
        self.fill_system(false);
        let system = self.system.clone();
        let rotation = self.rotation_now().cloned();
        let species_collisions = super::species::in_saved_order(
            &self.species,
            &self.species_collisions,
            &system.radii,
            &system.masses,
        );
        SpatialSnapshot {
            system,
            packing_fraction: phi,
            seed,
            options,
            time,
            steps,
            counters: tally,
            reference_velocity: [0.0; D],
            speed_bound: 0.0,
            draws: 0,
            temperature,
            species_collisions,
            tail: crate::tail::Tail {
                walls: self.walls_state(),
                shear: self.shear,
                virial: self.virial,
                tracks: self.tracks_in_order(),
                rotation,
                history: None,
            },
        }
    }

    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Particles on all ranks.
    pub fn len(&self) -> usize {
        self.total
    }

    pub fn is_empty(&self) -> bool {
        self.total == 0
    }

    /// The ranks of the run (1: this process alone).
    pub fn ranks(&self) -> usize {
        self.comm.size()
    }

    /// Width of the collision cells (the narrowest side of a cell in a box that is not a
    /// cube).
    pub fn cell_width(&self) -> f64 {
        self.widths().into_iter().fold(f64::INFINITY, f64::min)
    }

    /// Widths of the collision cells along each axis.
    fn widths(&self) -> [f64; D] {
        std::array::from_fn(|k| self.sides[k] / self.cells[k] as f64)
    }

    /// Number of collision cells.
    fn cell_count(&self) -> u64 {
        self.cells.iter().product()
    }

    /// Mean number of particles per collision cell.
    pub fn particles_per_cell(&self) -> f64 {
        if crate::system::is_cube(&self.sides) {
            self.len() as f64 / (self.cells[0] as f64).powi(D as i32)
        } else {
            self.len() as f64 / self.cell_count() as f64
        }
    }

    /// The temperature at the end of the last step (sets the next step).
    pub fn step_temperature(&self) -> f64 {
        self.temperature
    }

    /// Steps toward `end` and `target` (which choose the steps), pausing at `pause`.
    fn run(&mut self, end: f64, target: u64, pause: u64) {
        let n = self.len() as f64;
        while self.tally.collisions < target.min(pause) && self.time < end {
            let density = n * self.weight / crate::system::box_volume(&self.sides);
            let omega = frequency_estimate::<D>(&self.species, density, 1.0, self.temperature);
            if !positive(omega) {
                if end.is_finite() {
                    self.time = end;
                }
                return;
            }
            let mut dt = match self.options.step {
                StepSize::Auto => {
                    let speed = (self.temperature / self.species.min_mass).sqrt()
                        * theory::mean_norm_of_gaussian::<D>();
                    (0.2 / omega).min(0.5 * self.cell_width() / speed)
                }
                StepSize::CollisionsPerParticle(x) => x / omega,
                StepSize::Fixed(dt) => dt,
            };
            if target != u64::MAX {
                let remaining = (target - self.tally.collisions) as f64;
                dt = dt.min(2.0 * remaining / (n * omega));
            }
            let last = dt >= end - self.time;
            if last {
                dt = end - self.time;
            }
            self.step(dt);
            self.time = if last { end } else { self.time + dt };
        }
    }
}
