//! The saved state of a [`SoftSphere`] engine and its restore, checked.

use super::contact::ViscoelasticMaterial;
use super::neighbors::NeighborList;
use super::tangential::{ContactHistory, Rough};
use super::{
    empty_system, neighbor_skin, unknown, ContactStatistics, ContainerState, SoftSphere,
    SoftSphereOptions,
};
use crate::engine::{Checkpoint, Counters};
use crate::error::{require_positive, Error, Result};
use crate::shear::Virial;
use crate::system::{System, Vector};
use crate::tail::Tail;
use serde::{Deserialize, Serialize};

/// The saved state of a [`SoftSphere`] engine.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoftSphereState<const D: usize> {
    pub system: System<D>,
    /// Forces at the current positions (they depend on the predicted velocities of the
    /// step that computed them, so they are saved rather than recomputed).
    #[serde(with = "crate::serde_util::vectors")]
    pub forces: Vec<Vector<D>>,
    pub material: ViscoelasticMaterial,
    pub options: SoftSphereOptions,
    pub time_step: f64,
    pub time: f64,
    pub steps: u64,
    pub counters: Counters,
    /// Pairs in contact after the last step (i < j, sorted).
    pub contacts: Vec<(u32, u32)>,
    pub collision_counts: Vec<u32>,
    pub statistics: ContactStatistics,
    /// See [`accuracy::eps_error`] (absent in check-points written before it existed).
    #[serde(default = "unknown")]
    pub eps_error: f64,
    /// Walls and their contacts in a container, the shear, the tensor virial (absent from
    /// periodic unsheared runs' states, which stay as they were byte for byte; a container
    /// alone is written as the optional container that was the last field before:
    /// [`crate::tail::Tail`]).
    /// Rough spheres add their rotation and the contacts' tangential springs.
    #[serde(default, skip_serializing_if = "Tail::is_empty")]
    pub tail: Tail<ContainerState, ContactHistory>,
}

impl<const D: usize> Checkpoint<D> for SoftSphere<D> {
    type State = SoftSphereState<D>;
    type Needs = ();

    fn save(&mut self) -> SoftSphereState<D> {
        SoftSphereState {
            system: self.system.clone(),
            forces: self.forces.clone(),
            material: self.material,
            options: self.options,
            time_step: self.time_step,
            time: self.time,
            steps: self.steps,
            counters: self.tally,
            contacts: self.contacts.clone(),
            collision_counts: self.collision_counts.clone(),
            statistics: self.statistics,
            eps_error: self.eps_error,
            tail: Tail {
                walls: self.container_state(),
                shear: self.shear,
                virial: self.virial,
                tracks: self.tracks.clone(),
                rotation: self.rough.as_ref().map(|r| r.rotation.clone()),
                history: self.rough.as_ref().map(|r| r.history.clone()),
            },
        }
    }

    /// Continues the run of `state` bit for bit, after checking it (the force law is the
    /// state's material: a restore needs nothing else).
    fn restore(state: SoftSphereState<D>, _needs: ()) -> Result<Self> {
        let n = state.system.len();
        if state.forces.len() != n || state.collision_counts.len() != n {
            return Err(Error::LengthMismatch {
                what: "system, forces and collision counts".into(),
            });
        }
        state.material.validate()?;
        state.system.check(true)?;
        require_positive("time_step", state.time_step)?;
        if !(state.time.is_finite() && state.time >= 0.0) {
            return Err(Error::out_of_range(
                "time",
                state.time,
                "a finite time >= 0",
            ));
        }
        if state
            .contacts
            .iter()
            .any(|&(i, j)| i >= j || j as usize >= n)
            || state.contacts.windows(2).any(|w| w[0] >= w[1])
        {
            return Err(Error::out_of_range(
                "contacts",
                "(list)",
                "sorted pairs i < j of particle indices",
            ));
        }
        let skin = neighbor_skin(&state.options, &state.system)?;
        state.counters.check("")?;
        state.tail.check()?;
        if let Some(tracks) = &state.tail.tracks {
            tracks.check(D * n)?;
        }
        if let Some(shear) = &state.tail.shear {
            if state.tail.tracks.is_some() {
                return Err(Error::out_of_range(
                    "tracks",
                    "tracks of a sheared gas",
                    "none under shear (the flow carries spheres along x)",
                ));
            }
            if D < 2 || state.tail.walls.is_some() {
                return Err(Error::out_of_range(
                    "shear",
                    shear.rate,
                    "none in 1D or in a container",
                ));
            }
        }
        if let Some(i) = state
            .forces
            .iter()
            .position(|f| f.iter().any(|x| !x.is_finite()))
        {
            return Err(Error::NotFinite {
                what: "forces",
                index: i,
            });
        }
        // Radii and masses within the scales a run file allows (a mass of 1e-300 makes
        // any contact force overflow the velocities).
        for (what, list) in [
            ("radii", &state.system.radii),
            ("masses", &state.system.masses),
        ] {
            if let Some(i) = list.iter().position(|x| !(1e-30..=1e30).contains(x)) {
                return Err(Error::out_of_range(
                    format!("{what}[{i}]"),
                    list[i],
                    "1e-30 ..= 1e30",
                ));
            }
        }
        // No sphere may cross its own radius in a step: the step could not resolve its
        // contacts (and a wall's overlap would exceed its size). A run's time step resolves
        // contacts at its fastest impacts, orders of magnitude below this. Under shear the
        // speeds relative to the flow (a pair meets at its peculiar speeds).
        let shear = state.tail.shear;
        let smallest = state
            .system
            .radii
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        if let Some(i) = (state.system.positions.iter())
            .zip(&state.system.velocities)
            .position(|(x, v)| {
                let u = shear.map_or(*v, |s| s.peculiar(x[1], v));
                (0..D).map(|k| u[k] * u[k]).sum::<f64>().sqrt() * state.time_step > smallest
            })
        {
            return Err(Error::out_of_range(
                format!("velocities[{i}]"),
                format!("{:?}", state.system.velocities[i]),
                format!(
                    "speeds that move a sphere less than the smallest radius ({smallest}) per \
                     time step ({})",
                    state.time_step
                ),
            ));
        }
        // Forces that would kick the velocities of one step beyond the range of f64 (the
        // observers' sums of m u^2 and its square) come from a forged state, not a run.
        let (mut energy, mut fourth) = (0.0f64, 0.0f64);
        let s = &state.system;
        for ((v, f), &m) in s.velocities.iter().zip(&state.forces).zip(&s.masses) {
            let u2: f64 = (0..D)
                .map(|k| (v[k] + state.time_step * f[k] / m).powi(2))
                .sum();
            energy += m * u2;
            fourth += (m * u2).powi(2);
        }
        if !(energy.is_finite() && fourth.is_finite()) {
            return Err(Error::out_of_range(
                "forces",
                "forces that kick a step's velocities beyond the range of f64",
                "forces of the contacts of a run",
            ));
        }
        let overlap = state.statistics.max_relative_overlap;
        if !(overlap.is_finite() && overlap >= 0.0) {
            return Err(Error::out_of_range(
                "max_relative_overlap",
                overlap,
                "a finite number >= 0",
            ));
        }
        if !(state.eps_error.is_nan() || state.eps_error >= 0.0 && state.eps_error.is_finite()) {
            return Err(Error::out_of_range(
                "eps_error",
                state.eps_error,
                "a finite number >= 0 (or NaN: not recorded)",
            ));
        }
        let rough = restore_rough(&state)?;
        let twisted = |i: usize| {
            rough
                .as_ref()
                .is_some_and(|r| r.history.torques[i] != [0.0; 3])
        };
        let active = (0..n as u32)
            .filter(|&i| state.forces[i as usize].iter().any(|&f| f != 0.0) || twisted(i as usize))
            .collect();
        let tracked_positions = match state.tail.tracks {
            Some(_) => state.system.positions.clone(),
            None => Vec::new(),
        };
        let mut neighbors = NeighborList::new(skin);
        neighbors.sheared(state.tail.shear.map(|s| s.jump(&state.system.sides)));
        Ok(SoftSphere {
            active,
            touching: vec![0; n],
            current: Vec::new(),
            impulses: Vec::new(),
            neighbors,
            system: state.system,
            forces: state.forces,
            material: state.material,
            options: state.options,
            time_step: state.time_step,
            time: state.time,
            steps: state.steps,
            tally: state.counters,
            contacts: state.contacts,
            collision_counts: state.collision_counts,
            statistics: state.statistics,
            eps_error: state.eps_error,
            container: None,
            saved_container: state.tail.walls,
            restored_container: false,
            shear: state.tail.shear,
            virial: state.tail.virial,
            stress_rate: Virial::default(),
            view: empty_system(),
            tracked_positions,
            tracks: state.tail.tracks,
            friction: rough.as_ref().map(|r| r.history.friction),
            rough,
        })
    }
}

/// The rough side of a restored state, checked: a rotation and a contact history come
/// together, the history has a spring per contact and a torque per particle, all finite.
fn restore_rough<const D: usize>(state: &SoftSphereState<D>) -> Result<Option<Rough>> {
    let n = state.system.len();
    let (rotation, history) = match (&state.tail.rotation, &state.tail.history) {
        (None, None) => return Ok(None),
        (Some(r), Some(h)) => (r.clone(), h.clone()),
        _ => {
            return Err(Error::out_of_range(
                "rotation",
                "a rotation without the contacts' springs, or the other way",
                "both for rough spheres, neither for smooth ones",
            ))
        }
    };
    rotation.check(n, D)?;
    Rough::check_friction(history.friction)?;
    if history.springs.len() != state.contacts.len() || history.torques.len() != n {
        return Err(Error::LengthMismatch {
            what: "contacts and springs, particles and torques".into(),
        });
    }
    let finite = |v: &[f64; 3]| v.iter().all(|x| x.is_finite());
    if let Some(i) = history.torques.iter().position(|t| !finite(t)) {
        return Err(Error::NotFinite {
            what: "torques",
            index: i,
        });
    }
    if let Some(i) = history
        .springs
        .iter()
        .position(|s| !finite(&s.displacement))
    {
        return Err(Error::NotFinite {
            what: "springs",
            index: i,
        });
    }
    if !(history.stored.is_finite() && history.stored >= 0.0) {
        return Err(Error::out_of_range(
            "stored",
            history.stored,
            "a finite spring energy >= 0",
        ));
    }
    Ok(Some(Rough {
        history,
        rotation,
        aligned: Vec::new(),
        fresh: Vec::new(),
        twists: Vec::new(),
    }))
}
