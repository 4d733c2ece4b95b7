//! Force-based soft-sphere molecular dynamics (DEM) of viscoelastic spheres: the normal
//! force of Eq. (2) of Müller & Pöschel 2011 ([`contact`]) between every pair of
//! overlapping spheres, integrated in time steps, with Verlet neighbour lists
//! ([`neighbors`]) in a periodic box, 1D to 3D. The engine that the event-driven engine
//! with the exact coefficient of restitution replaces: the same gas run both ways shows
//! where the binary-collision idealization holds (dilute gases) and where it fails
//! (multi-particle contacts, contacts as long as the free flight).
//!
//! The integrator is velocity Verlet (kick–drift–kick), symplectic for the elastic Hertz
//! force. The dissipative force depends on the velocity, which velocity Verlet knows only
//! half a step late; the force at t + dt is evaluated with the predicted velocity
//! v(t + dt/2) + (dt/2) F(t)/m, correct to O(dt²), so that the scheme stays second order
//! (test `two_particle_eps_converges_at_second_order`).
//!
//! The time step is a fraction 1/`steps_per_contact` of the Hertz contact duration
//! ([`contact::hertz_duration`]) at a high relative speed of the initial gas (ten thermal
//! speeds sqrt(T/m) of the lightest species), for the stiffest pair of species: faster
//! collisions are shorter, so a cooling gas is resolved ever better.
//!
//! Counters: a collision is a contact begun (a pair whose overlap turned positive); the
//! energy lost is the work of the dissipative forces, ∫ F_dis ξ̇ dt (trapezoidal per step).
//! While the force is clamped to zero (F_dis = −ρ ξ^{3/2}) that work is the elastic energy
//! the separating pair gives up, so that kinetic energy + elastic energy of the overlaps
//! ([`SoftSphere::elastic_energy`]) + energy lost is conserved, and after a contact the energy
//! lost is its kinetic-energy loss, (1 − ε²) m_eff v² / 2 as in the event-driven engine;
//! the virial is ∫ Σ F_n d dt over the pairs in contact, so that its rate is the
//! collisional virial of [`crate::observe::pressure`]. The tensor virial
//! ([`SoftSphere::set_virial_tensor`]) is ∫ Σ F_n d n n dt over the same contacts, its trace
//! the virial, so that its increment over an interval Δt divided by V Δt is the time
//! average of the collisional stress (Allen & Tildesley, Sec. 2.4;
//! [`crate::observe::pressure_tensor`]).
//!
//! Uniform shear flow: Lees–Edwards boundaries (`soft/lees_edwards.rs`,
//! [`SoftSphere::set_shear`]).
//!
//! Rough spheres and disks ([`SoftSphere::set_friction`] and a rotation): the tangential
//! force of [`tangential`] (a Cundall–Strack spring of Mindlin's stiffness, damped, cut at
//! Coulomb's limit) and its torques, the angular velocities integrated by the same
//! velocity Verlet; the energy the springs hold counts with the elastic energy.

pub mod accuracy;
mod container;
pub use container::ContainerState;
pub mod contact;
mod lees_edwards;
pub mod neighbors;
pub mod oblique;
mod state;
mod step;
pub mod tangential;
mod tracking;
pub use state::SoftSphereState;
pub use tangential::{ContactHistory, Spring};

use crate::engine::{Counters, Engine, Report, ReportSection, ReportValue};
use crate::error::{require_positive, Error, Result};
use crate::shear::{Shear, Virial};
use crate::system::{minimum_image, wrap, System, Vector};
use contact::{contact_duration, ViscoelasticMaterial};
use neighbors::NeighborList;
use serde::{Deserialize, Serialize};

/// Time steps per Hertz contact duration when none is given.
pub const DEFAULT_STEPS_PER_CONTACT: f64 = 50.0;

/// Skin of the neighbour lists, in units of the largest diameter, when none is given.
pub const DEFAULT_SKIN: f64 = 0.3;

/// Options of [`SoftSphere`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoftSphereOptions {
    /// A fixed time step; None: the Hertz duration over `steps_per_contact`.
    pub time_step: Option<f64>,
    /// Time steps per contact duration (>= 4).
    pub steps_per_contact: f64,
    /// Neighbour-list skin in largest diameters (> 0).
    pub skin: f64,
}

impl Default for SoftSphereOptions {
    fn default() -> Self {
        SoftSphereOptions {
            time_step: None,
            steps_per_contact: DEFAULT_STEPS_PER_CONTACT,
            skin: DEFAULT_SKIN,
        }
    }
}

/// What the contacts did, beyond the counters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactStatistics {
    /// The largest overlap seen, over the contact distance R_i + R_j.
    pub max_relative_overlap: f64,
    /// Particle-steps in contact with at least one other particle.
    pub contact_steps: u64,
    /// Particle-steps in contact with two or more others at once (multi-particle
    /// contacts, which the binary-collision picture of eMD and DSMC leaves out).
    pub multi_contact_steps: u64,
}

impl ContactStatistics {
    /// The fraction of the time in contact that a particle spends in multi-particle
    /// contacts (0 if never in contact).
    pub fn multi_contact_fraction(&self) -> f64 {
        if self.contact_steps == 0 {
            0.0
        } else {
            self.multi_contact_steps as f64 / self.contact_steps as f64
        }
    }
}

/// A soft-sphere run's contacts for reports (`summary.json`, Python): the time step, the
/// [`ContactStatistics`] so far, and the pairs in contact now with the elastic energy they
/// hold, which the kinetic temperature does not count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactReport {
    pub time_step: f64,
    /// Time steps taken.
    pub steps: u64,
    /// Pairs overlapping now.
    pub contacts_now: usize,
    /// Elastic energy of the overlaps now, Σ (2/5) ρ ξ^{5/2} (the potential of the Hertz
    /// force ρ ξ^{3/2}).
    pub elastic_energy: f64,
    /// See [`ContactStatistics`].
    pub max_relative_overlap: f64,
    pub contact_steps: u64,
    pub multi_contact_steps: u64,
    /// [`ContactStatistics::multi_contact_fraction`].
    pub multi_contact_fraction: f64,
    /// How well the time step resolves isolated contacts: the largest |eps(MD) − eps(exact
    /// law)| of head-on contacts at 0.1, 1 and 10 initial thermal speeds
    /// ([`accuracy::eps_error`]).
    pub eps_error: f64,
}

impl ContactReport {
    /// As the section `contacts` of an engine's [`Report`] (`summary.json`: `contacts`).
    pub fn section(&self) -> ReportSection {
        use ReportValue::{Count, Real};
        ReportSection {
            name: "contacts",
            values: vec![
                ("time_step", Real(self.time_step)),
                ("steps", Count(self.steps)),
                ("contacts_now", Count(self.contacts_now as u64)),
                ("elastic_energy", Real(self.elastic_energy)),
                ("max_relative_overlap", Real(self.max_relative_overlap)),
                ("contact_steps", Count(self.contact_steps)),
                ("multi_contact_steps", Count(self.multi_contact_steps)),
                ("multi_contact_fraction", Real(self.multi_contact_fraction)),
                ("eps_error", Real(self.eps_error)),
            ],
        }
    }
}

/// The neighbour list's skin, `options.skin` largest diameters, after checking that it is
/// positive and that the box holds twice the largest diameter plus the skin (one image).
fn neighbor_skin<const D: usize>(options: &SoftSphereOptions, system: &System<D>) -> Result<f64> {
    if !(options.skin.is_finite() && options.skin > 0.0) {
        return Err(Error::out_of_range(
            "skin",
            options.skin,
            "a finite number > 0",
        ));
    }
    let largest = 2.0 * system.radii.iter().copied().fold(0.0, f64::max);
    let skin = options.skin * largest;
    if system.shortest_side() < 2.0 * (largest + skin) {
        return Err(Error::out_of_range(
            "length",
            system.shortest_side(),
            format!(
                "at least twice the largest diameter plus the skin, {}",
                2.0 * (largest + skin)
            ),
        ));
    }
    Ok(skin)
}

/// NaN: a quantity a check-point did not record.
fn unknown() -> f64 {
    f64::NAN
}

/// Soft-sphere MD of viscoelastic spheres (see the [module](self) documentation).
pub struct SoftSphere<const D: usize> {
    system: System<D>,
    forces: Vec<Vector<D>>,
    material: ViscoelasticMaterial,
    options: SoftSphereOptions,
    time_step: f64,
    time: f64,
    steps: u64,
    tally: Counters,
    contacts: Vec<(u32, u32)>,
    collision_counts: Vec<u32>,
    statistics: ContactStatistics,
    /// See [`accuracy::eps_error`] (NaN for the engines the probe builds).
    eps_error: f64,
    neighbors: NeighborList,
    /// The particles in contact at the last force computation, the only ones whose force
    /// may be nonzero (for a restored engine: those whose force is nonzero).
    active: Vec<u32>,
    /// Scratch: contacts of each particle in the current step (zero outside `active`).
    touching: Vec<u8>,
    /// Scratch: the contacts of the current step.
    current: Vec<(u32, u32)>,
    /// Scratch: the force on the second particle of each pair of `current`.
    impulses: Vec<Vector<D>>,
    /// Walls and gravity ([`SoftSphere::set_walls`], [`SoftSphere::set_gravity`]).
    container: Option<container::Container<D>>,
    /// The container's state from a check-point, taken up by the next `set_walls`.
    saved_container: Option<ContainerState>,
    /// Whether the container came from a check-point (its forces are then the saved ones).
    restored_container: bool,
    /// Lees–Edwards boundaries ([`SoftSphere::set_shear`]); None: periodic.
    shear: Option<Shear>,
    /// The tensor virial ∫ Σ F_n d n n dt, if asked for ([`SoftSphere::set_virial_tensor`]).
    virial: Option<Virial>,
    /// Scratch: the rate Σ F_n d n n of the last force computation (with the tensor virial).
    stress_rate: Virial,
    /// Under shear, the state with the peculiar velocities ([`Engine::system`]).
    view: System<D>,
    /// The displacements since tracking began ([`SoftSphere::set_tracking`]), and the
    /// positions after the last step they were followed to.
    tracks: Option<crate::tail::Tracks>,
    tracked_positions: Vec<Vector<D>>,
    /// Coulomb's friction coefficient of rough contacts ([`SoftSphere::set_friction`]).
    friction: Option<f64>,
    /// Rough particles: their rotation and the contacts' tangential springs (with a
    /// friction and a rotation).
    rough: Option<tangential::Rough>,
}

impl<const D: usize> SoftSphere<D> {
    /// An engine at time 0 from `system` (positions wrapped into the box; overlapping
    /// spheres are allowed and repel) with the material of every sphere and the options.
    /// Fails, naming the parameter, for bad input.
    /// The engine reports how well its time step resolves isolated contacts
    /// ([`accuracy::eps_error`]).
    pub fn new(
        system: System<D>,
        material: ViscoelasticMaterial,
        options: SoftSphereOptions,
    ) -> Result<Self> {
        let mut engine = Self::build(system, material, options)?;
        engine.eps_error = accuracy::eps_error(&engine.system, material, engine.time_step)?;
        // A step too coarse for the contacts (too few steps for strongly damped ones, whose
        // damping the explicit scheme then overshoots) gives a silently different run, or
        // NaN: refused, naming the option that set the step.
        if engine.eps_error.is_nan() || engine.eps_error > accuracy::MAX_EPS_ERROR {
            let allowed = format!(
                "a step that resolves contacts: eps of isolated contacts within {} of the exact \
                 law (this step: {:.2e}); more steps per contact",
                accuracy::MAX_EPS_ERROR,
                engine.eps_error
            );
            let (name, value) = match options.time_step {
                Some(dt) => ("time_step", dt),
                None => ("steps_per_contact", options.steps_per_contact),
            };
            return Err(Error::UnresolvedStep {
                name,
                value,
                allowed,
            });
        }
        Ok(engine)
    }

    /// [`SoftSphere::new`] without the accuracy probe (which builds engines of its own).
    pub(crate) fn build(
        system: System<D>,
        material: ViscoelasticMaterial,
        options: SoftSphereOptions,
    ) -> Result<Self> {
        material.validate()?;
        system.check(false)?;
        let mut system = system;
        let sides = system.sides;
        for x in &mut system.positions {
            for (c, &l) in x.iter_mut().zip(&sides) {
                *c = wrap(*c, l);
            }
        }
        let time_step = match options.time_step {
            Some(dt) => require_positive("time_step", dt)?,
            None => {
                if !(options.steps_per_contact.is_finite() && options.steps_per_contact >= 4.0) {
                    return Err(Error::out_of_range(
                        "steps_per_contact",
                        options.steps_per_contact,
                        "a finite number >= 4",
                    ));
                }
                shortest_contact(&system, &material)? / options.steps_per_contact
            }
        };
        let skin = neighbor_skin(&options, &system)?;
        let n = system.len();
        let mut engine = SoftSphere {
            forces: vec![[0.0; D]; n],
            material,
            options,
            time_step,
            time: 0.0,
            steps: 0,
            tally: Counters::default(),
            contacts: Vec::new(),
            collision_counts: vec![0; n],
            statistics: ContactStatistics::default(),
            eps_error: f64::NAN,
            neighbors: NeighborList::new(skin),
            active: Vec::new(),
            touching: vec![0; n],
            current: Vec::new(),
            impulses: Vec::new(),
            container: None,
            saved_container: None,
            restored_container: false,
            shear: None,
            virial: None,
            stress_rate: Virial::default(),
            view: empty_system(),
            tracks: None,
            tracked_positions: Vec::new(),
            friction: None,
            rough: None,
            system,
        };
        // Forces of the initial state (velocities known exactly at t = 0); overlaps present
        // at t = 0 are contacts begun.
        let (_, _, begun) = engine.compute_forces(None);
        engine.tally.collisions += begun;
        Ok(engine)
    }

    /// The time step.
    pub fn time_step(&self) -> f64 {
        self.time_step
    }

    /// Takes `n` full time steps.
    pub fn run_steps(&mut self, n: u64) {
        for _ in 0..n {
            self.step(self.time_step);
            self.time += self.time_step;
            self.follow_tracks();
        }
    }

    /// Neighbour-list builds so far (in this process: a restored engine counts from 0).
    pub fn neighbor_builds(&self) -> u64 {
        self.neighbors.builds
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// What the contacts did so far ([`ContactReport`]).
    pub fn contact_report(&self) -> ContactReport {
        let s = self.statistics;
        ContactReport {
            time_step: self.time_step,
            steps: self.steps,
            contacts_now: self.contacts.len(),
            elastic_energy: self.elastic_energy(),
            max_relative_overlap: s.max_relative_overlap,
            contact_steps: s.contact_steps,
            multi_contact_steps: s.multi_contact_steps,
            multi_contact_fraction: s.multi_contact_fraction(),
            eps_error: self.eps_error,
        }
    }

    /// Overlaps, contacts and multi-particle contacts so far.
    pub fn statistics(&self) -> ContactStatistics {
        self.statistics
    }

    /// Pairs in contact now.
    pub fn contacts(&self) -> &[(u32, u32)] {
        &self.contacts
    }

    /// The material.
    pub fn material(&self) -> ViscoelasticMaterial {
        self.material
    }

    /// Elastic energy held in the overlaps now, Σ (2/5) ρ ξ^{5/2} over the pairs in
    /// contact, and in the tangential springs of rough contacts, Σ (1/2) k_t |δ|².
    pub fn elastic_energy(&self) -> f64 {
        self.normal_elastic_energy() + self.rough.as_ref().map_or(0.0, |r| r.history.stored)
    }

    /// Σ (2/5) ρ ξ^{5/2} over the pairs in contact.
    fn normal_elastic_energy(&self) -> f64 {
        let s = &self.system;
        let images = self.images_at(self.time);
        self.contacts
            .iter()
            .map(|&(i, j)| {
                let (i, j) = (i as usize, j as usize);
                let d2: f64 = match &images {
                    Some(im) => {
                        let (r, _) = im.separation(&s.positions[i], &s.positions[j], &s.sides);
                        r.iter().map(|x| x * x).sum()
                    }
                    None => (0..D)
                        .map(|k| {
                            minimum_image(s.positions[j][k] - s.positions[i][k], s.sides[k]).powi(2)
                        })
                        .sum(),
                };
                let xi = (s.radii[i] + s.radii[j] - d2.sqrt()).max(0.0);
                0.4 * self.material.elastic_constant(s.radii[i], s.radii[j]) * xi.powf(2.5)
            })
            .sum()
    }

    /// Sums the tensor virial of the contacts from now on (`true`, from zero unless it is
    /// summed already) or stops (`false`).
    pub fn set_virial_tensor(&mut self, on: bool) {
        if !on {
            self.virial = None;
        } else if self.virial.is_none() {
            self.virial = Some(Virial::default());
        }
    }

    /// Steps while the time is below `end`, the collisions below `collisions` and below
    /// `pause`; the last step before `end` is shortened to end there, so that samples fall
    /// on their times (pieces of a run compose bit for bit: the steps depend only on the
    /// targets).
    fn run_to(&mut self, end: f64, collisions: u64, pause: u64) {
        while self.time < end && self.tally.collisions < collisions.min(pause) {
            if self.time + self.time_step < end {
                self.step(self.time_step);
                self.time += self.time_step;
            } else {
                self.step(end - self.time);
                self.time = end;
            }
            self.follow_tracks();
        }
    }
}

/// A system of no particles (the buffer of [`SoftSphere`]'s peculiar view).
fn empty_system<const D: usize>() -> System<D> {
    System {
        sides: [1.0; D],
        positions: Vec::new(),
        velocities: Vec::new(),
        radii: Vec::new(),
        masses: Vec::new(),
    }
}

/// The distinct (radius, mass) of the particles of `system`, sorted.
fn species<const D: usize>(system: &System<D>) -> Vec<(f64, f64)> {
    let mut kinds: Vec<(f64, f64)> = system
        .radii
        .iter()
        .zip(&system.masses)
        .map(|(&r, &m)| (r, m))
        .collect();
    kinds.sort_by(|a, b| a.partial_cmp(b).expect("finite radii and masses"));
    kinds.dedup();
    kinds
}

/// The thermal speed sqrt(T/m) of the lightest of the species `kinds` (radius, mass).
fn thermal_speed(kinds: &[(f64, f64)], temperature: f64) -> f64 {
    let lightest = kinds.iter().map(|k| k.1).fold(f64::INFINITY, f64::min);
    (temperature / lightest).sqrt()
}

/// The shortest contact duration ([`contact_duration`], damping included) among the pairs
/// of species of `system`, at ten thermal speeds sqrt(T/m) of the lightest species: faster
/// contacts are shorter, Hertz's as v^{−1/5} and damped ones more so.
fn shortest_contact<const D: usize>(
    system: &System<D>,
    material: &ViscoelasticMaterial,
) -> Result<f64> {
    let kinds = species(system);
    let temperature = crate::observe::temperature(system).max(f64::MIN_POSITIVE);
    shortest_contact_duration(&kinds, temperature, material)
}

/// The contact duration the default time step resolves: the shortest among the pairs of
/// the species `kinds` (radius, mass) at ten thermal speeds sqrt(T/m) of the lightest, at
/// temperature T (see [`SoftSphereOptions::steps_per_contact`]).
pub fn shortest_contact_duration(
    kinds: &[(f64, f64)],
    temperature: f64,
    material: &ViscoelasticMaterial,
) -> Result<f64> {
    let speed = 10.0 * thermal_speed(kinds, temperature);
    let mut shortest = f64::INFINITY;
    for (a, &(r1, m1)) in kinds.iter().enumerate() {
        for &(r2, m2) in &kinds[a..] {
            let rho = material.elastic_constant(r1, r2);
            let duration = contact_duration(
                rho,
                material.dissipative_constant,
                m1 * m2 / (m1 + m2),
                speed,
            )?;
            shortest = shortest.min(duration);
        }
    }
    Ok(shortest)
}

impl<const D: usize> Engine<D> for SoftSphere<D> {
    fn walls(&self) -> Option<Vec<crate::walls::WallRecord>> {
        self.container.as_ref().map(|c| c.walls.records())
    }

    fn run_until(&mut self, t: f64) {
        self.run_to(t, u64::MAX, u64::MAX);
    }

    fn run_collisions(&mut self, collisions: u64) {
        let target = self.tally.collisions.saturating_add(collisions);
        self.run_to(f64::INFINITY, target, u64::MAX);
    }

    fn run_paused(&mut self, end: f64, collisions: u64, pause: u64) {
        self.run_to(end, collisions, pause);
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn counters(&self) -> Counters {
        self.tally
    }

    fn particles(&self) -> usize {
        self.system.len()
    }

    /// The state; under shear, velocities relative to the flow (peculiar: v − a y e_x).
    fn system(&mut self) -> &System<D> {
        match self.shear {
            None => &self.system,
            Some(shear) => {
                self.fill_view(shear);
                &self.view
            }
        }
    }

    fn shear(&self) -> Option<Shear> {
        SoftSphere::shear(self)
    }

    fn set_shear(&mut self, shear: Option<Shear>) -> Result<()> {
        SoftSphere::set_shear(self, shear)
    }

    fn set_tracking(&mut self, on: bool) -> Result<()> {
        SoftSphere::set_tracking(self, on)
    }

    /// The displacements in the engine's (fixed) order.
    fn displacements(&mut self) -> Option<Vec<Vector<D>>> {
        SoftSphere::displacements(self)
    }

    /// The tensor virial ∫ Σ F_n d n n dt summed so far, if asked for.
    fn virial_tensor(&self) -> Option<Virial> {
        self.virial
    }

    fn set_virial_tensor(&mut self, on: bool) -> Result<()> {
        SoftSphere::set_virial_tensor(self, on);
        Ok(())
    }

    fn collision_counts(&self) -> Option<Vec<u32>> {
        Some(self.collision_counts.clone())
    }

    fn set_rotation(&mut self, rotation: Option<crate::rotation::Rotation>) -> Result<()> {
        SoftSphere::set_rotation(self, rotation)
    }

    fn rotation(&mut self) -> Option<&crate::rotation::Rotation> {
        self.rough.as_ref().map(|r| &r.rotation)
    }

    /// The contacts (section `contacts`: [`ContactReport`]) and, for rough spheres, their
    /// rotation (section `rotation`: the contacts that slid).
    fn report(&self) -> Report {
        let mut sections = vec![self.contact_report().section()];
        if let Some(rough) = &self.rough {
            sections.push(rough.rotation.report(self.tally.collisions));
        }
        Report { sections }
    }

    fn memory_bytes(&self) -> usize {
        let n = self.system.len();
        n * (std::mem::size_of::<Vector<D>>() * 3 + 16 + 5)
            + self.contacts.capacity() * 8
            + self.current.capacity() * 8
            + self.active.capacity() * 4
            + self.impulses.capacity() * std::mem::size_of::<Vector<D>>()
            + self.neighbors.memory_bytes()
            + self.view.velocities.capacity() * std::mem::size_of::<Vector<D>>() * 2
            + self.view.radii.capacity() * 16
            + self.rough.as_ref().map_or(0, |r| {
                (r.history.torques.capacity() + r.rotation.angular.capacity()) * 24
                    + r.rotation.inertia.capacity() * 8
                    + (r.history.springs.capacity() + r.aligned.capacity()) * 32
                    + r.twists.capacity() * 24
            })
    }
}
