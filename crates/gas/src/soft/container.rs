//! Walls and gravity in soft-sphere MD. A wall is a contact of the sphere's own material
//! with a half-space (Hertz with R_eff = R, the wall infinitely massive): the force of
//! Eq. (2) of Müller & Pöschel 2011 with ρ_w = 2 Y √R / (3 (1 − ν²)) and the material's
//! dissipative constant A (kind "elastic": A = 0), at the overlap ξ = R − (distance of the
//! centre from the wall's plane) and its rate, the plane moving as a vibrating wall
//! prescribes. Its coefficient of restitution is then the viscoelastic one of
//! β_w = (3/2) A (ρ_w / m)^{2/5} (tested against [`restitution::exact`]). Gravity adds m g
//! to every force. The wall's tallies per step (trapezoid rule, like `energy_lost`): the
//! normal momentum it took, ∫ F dt, and the energy it gave, ∫ (F V_w − F_dis ξ̇) dt (its
//! work minus what its contact dissipated); contacts begun count as its collisions.

use super::contact::normal_force;
use super::SoftSphere;
use crate::error::{Error, Result};
use crate::system::Vector;
use crate::walls::{Side, WallKind, Walls, WallsState};
use serde::{Deserialize, Serialize};

/// The container's part of a saved state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContainerState {
    pub walls: WallsState,
    /// Bit w of entry i: sphere i touched wall w at the last force computation.
    pub touching: Vec<u8>,
    /// Per wall at the last force computation: (power given, normal force).
    pub rates: Vec<(f64, f64)>,
}

/// The walls and gravity of an engine.
#[derive(Debug)]
pub(super) struct Container<const D: usize> {
    pub(super) walls: Walls<D>,
    pub(super) gravity: Option<Vector<D>>,
    pub(super) touching: Vec<u8>,
    pub(super) rates: Vec<(f64, f64)>,
    /// This step's (contacts begun, power given, normal force) per wall.
    pub(super) step: Vec<(u64, f64, f64)>,
    /// The wall forces of this step: (sphere, axis, signed force along it).
    pub(super) pushes: Vec<(u32, usize, f64)>,
}

impl<const D: usize> SoftSphere<D> {
    /// Puts the gas into a container with `walls` (None: periodic again). Fails for a
    /// thermal wall (a soft contact has no temperature), a sphere whose centre is not
    /// inside the walls, or vibrating walls sweeping the box. Takes up the walls' state
    /// from a restored check-point (its forces stay as saved).
    pub fn set_walls(&mut self, walls: Option<Walls<D>>) -> Result<()> {
        let Some(mut walls) = walls else {
            if self.saved_container.is_some() {
                return Err(Error::out_of_range(
                    "walls",
                    "none",
                    "the walls the check-point was saved with",
                ));
            }
            self.container = None;
            self.neighbors.closed = 0;
            self.neighbors.invalidate();
            return Ok(());
        };
        if self.shear.is_some() {
            return Err(Error::out_of_range(
                "walls",
                "a sheared gas",
                "a periodic box under shear (Lees-Edwards boundaries)",
            ));
        }
        if walls
            .walls()
            .iter()
            .any(|w| matches!(w.kind, WallKind::Thermal { .. }))
        {
            return Err(Error::out_of_range(
                "wall.kind",
                "thermal",
                "elastic, restitution (the material's contact) or vibrating in soft-sphere MD",
            ));
        }
        let sides = self.system.sides;
        let largest = self.system.radii.iter().copied().fold(0.0, f64::max);
        walls.check_sweeps(&sides, 2.0 * largest)?;
        for k in (0..D).filter(|&k| walls.closed(k)) {
            let length = sides[k];
            let (low, high) = (
                walls.displacement(k, Side::Low, self.time),
                length - walls.displacement(k, Side::High, self.time),
            );
            if let Some(i) = self
                .system
                .positions
                .iter()
                .position(|x| !(x[k] > low && x[k] < high))
            {
                return Err(Error::out_of_range(
                    "wall",
                    format!("sphere {i} at {} on axis {k}", self.system.positions[i][k]),
                    format!("centres inside the walls ({low} .. {high})"),
                ));
            }
        }
        let n = self.system.len();
        let count = walls.walls().len();
        let restored = self.saved_container.take();
        let (touching, rates) = match &restored {
            Some(saved) => {
                if saved.touching.len() != n || saved.rates.len() != count {
                    return Err(Error::LengthMismatch {
                        what: "saved wall contacts and walls".into(),
                    });
                }
                walls.set_state(saved.walls.clone())?;
                (saved.touching.clone(), saved.rates.clone())
            }
            None => (vec![0; n], vec![(0.0, 0.0); count]),
        };
        let container = Container {
            walls,
            gravity: None,
            touching,
            rates,
            step: vec![(0, 0.0, 0.0); count],
            pushes: Vec::new(),
        };
        self.neighbors.closed = (0..D)
            .filter(|&k| container.walls.closed(k))
            .fold(0, |m, k| m | 1 << k);
        self.neighbors.invalidate();
        self.container = Some(container);
        self.restored_container = restored.is_some();
        if !self.restored_container {
            self.refresh_forces();
        }
        Ok(())
    }

    /// Lets every sphere fall with the acceleration `g` (None: none). Gravity needs walls
    /// on both sides of every axis it acts along ([`Self::set_walls`] first).
    pub fn set_gravity(&mut self, g: Option<Vector<D>>) -> Result<()> {
        let g = g.filter(|g| g.iter().any(|&x| x != 0.0));
        let Some(container) = self.container.as_mut() else {
            return match g {
                None => Ok(()),
                Some(g) => Err(Error::out_of_range(
                    "gravity",
                    format!("{g:?}"),
                    "components along axes closed by walls only",
                )),
            };
        };
        if let Some(g) = &g {
            crate::walls::fit_gravity(Some(&mut container.walls), g, 0.0)?;
        }
        container.gravity = g;
        if !self.restored_container {
            self.refresh_forces();
        }
        Ok(())
    }

    /// The walls, if the gas is in a container.
    pub fn walls(&self) -> Option<&Walls<D>> {
        self.container.as_ref().map(|c| &c.walls)
    }

    /// The container's state to save.
    pub(super) fn container_state(&self) -> Option<ContainerState> {
        self.container.as_ref().map(|c| ContainerState {
            walls: c.walls.state(),
            touching: c.touching.clone(),
            rates: c.rates.clone(),
        })
    }

    /// Forces of the current state again (walls or gravity changed at the start of a
    /// run), without counting its contacts twice.
    pub(super) fn refresh_forces(&mut self) {
        let statistics = self.statistics;
        self.compute_forces(None);
        self.statistics = statistics;
        if let Some(c) = self.container.as_mut() {
            c.rates = c.step.iter().map(|&(_, p, f)| (p, f)).collect();
        }
    }

    /// The wall forces at the current positions (velocities predicted as the pairs' are by
    /// `velocity`), the plane positions at the time of the positions: records them in the
    /// container's `pushes` and `step` (called before the forces are cleared).
    pub(super) fn find_wall_contacts(&mut self, predicting: Option<f64>) {
        let SoftSphere {
            container,
            system: s,
            forces,
            material,
            time,
            ..
        } = self;
        let Some(c) = container.as_mut() else {
            return;
        };
        let t = *time + predicting.unwrap_or(0.0);
        let a = material.dissipative_constant;
        c.pushes.clear();
        c.step.iter_mut().for_each(|x| *x = (0, 0.0, 0.0));
        for (w, wall) in c.walls.walls().iter().enumerate() {
            let k = wall.axis;
            let damping = if matches!(wall.kind, WallKind::Elastic) {
                0.0
            } else {
                a
            };
            let (plane, speed) = c
                .walls
                .motion(w)
                .map_or((0.0, 0.0), |m| (m.displacement(t), m.velocity(t)));
            let inward = match wall.side {
                Side::Low => 1.0,
                Side::High => -1.0,
            };
            let bit = 1u8 << w;
            #[allow(clippy::needless_range_loop)] // i indexes five arrays
            for i in 0..s.len() {
                let r = s.radii[i];
                // Distance of the centre from the plane, inward.
                let distance = match wall.side {
                    Side::Low => s.positions[i][k] - plane,
                    Side::High => s.sides[k] - plane - s.positions[i][k],
                };
                if distance >= r {
                    c.touching[i] &= !bit;
                    continue;
                }
                let v = match predicting {
                    Some(dt) => s.velocities[i][k] + 0.5 * dt / s.masses[i] * forces[i][k],
                    None => s.velocities[i][k],
                };
                let xi = r - distance;
                // ξ̇ = −(inward velocity of the sphere relative to the wall's).
                let xi_dot = -(inward * v - speed);
                let (force, dissipative) =
                    normal_force(material.wall_constant(r), damping, xi, xi_dot);
                c.pushes.push((i as u32, k, inward * force));
                let step = &mut c.step[w];
                if c.touching[i] & bit == 0 {
                    step.0 += 1;
                    c.touching[i] |= bit;
                }
                step.1 += force * speed - dissipative * xi_dot;
                step.2 += force;
            }
        }
    }

    /// Adds gravity and the wall forces found by [`Self::find_wall_contacts`] to the
    /// forces, and their spheres to `active` (called after the pairs' forces are set).
    pub(super) fn add_container_forces(&mut self) {
        let SoftSphere {
            container,
            forces,
            system,
            active,
            touching,
            ..
        } = self;
        let Some(c) = container.as_ref() else {
            return;
        };
        if let Some(g) = c.gravity {
            for (f, &m) in forces.iter_mut().zip(&system.masses) {
                for k in 0..D {
                    f[k] += m * g[k];
                }
            }
            // Every sphere has a force.
            active.clear();
            active.extend(0..system.len() as u32);
            for &(i, k, f) in &c.pushes {
                forces[i as usize][k] += f;
            }
            return;
        }
        for &(i, k, f) in &c.pushes {
            let i = i as usize;
            if touching[i] == 0 {
                touching[i] = 1;
                active.push(i as u32);
            }
            forces[i][k] += f;
        }
    }

    /// Tallies the walls' step of length dt (trapezoid between the last force computation
    /// and this one).
    pub(super) fn tally_walls(&mut self, dt: f64) {
        let Some(c) = self.container.as_mut() else {
            return;
        };
        for (w, (&(begun, power, force), rate)) in c.step.iter().zip(c.rates.iter_mut()).enumerate()
        {
            c.walls.add_work(
                w,
                begun,
                0.5 * dt * (rate.1 + force),
                0.5 * dt * (rate.0 + power),
            );
            *rate = (power, force);
        }
    }
}
