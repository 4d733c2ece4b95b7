//! Uniform shear flow in the spatial DSMC: Lees–Edwards boundaries (`crate::shear`). The
//! velocities are the lab frame's; a particle that streams through the upper face of the
//! box re-enters through the lower one as its image (y - L_y, x - δ, v_x - a L_y), with
//! the images' offset δ at the end of the step (the image relation holds at every time,
//! and the position is the one at the end of the free flight). Collisions happen among the
//! particles of a cell with their lab velocities, whose differences are the relative
//! velocities of the local frame. On several ranks the crossing is part of the stream and
//! the particle migrates by its new place like any other.

use super::super::kernel::Simulator;
use super::record::{each, with_records, Particle};
use super::SpatialDsmc;
use crate::error::{Error, Result};
use crate::shear::Shear;
use crate::system::{wrap, Vector};

/// What a stream needs of the sliding faces: the velocity jump a L_y and the images'
/// offset at the end of the step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Faces {
    jump: f64,
    offset: f64,
}

/// Streams particle `p` for `dt` (wrapped into the box; through a sliding face as its image).
#[inline(always)]
pub(super) fn stream_one<const D: usize>(
    p: &mut Simulator<D>,
    dt: f64,
    sides: &Vector<D>,
    faces: Option<Faces>,
) {
    let Some(faces) = faces else {
        for (k, x) in p.position.iter_mut().enumerate() {
            *x = wrap(*x + p.velocity[k] * dt, sides[k]);
        }
        return;
    };
    let mut x: Vector<D> = std::array::from_fn(|k| p.position[k] + p.velocity[k] * dt);
    let height = sides[1];
    if x[1] >= height {
        x[1] -= height;
        x[0] -= faces.offset;
        p.velocity[0] -= faces.jump;
    } else if x[1] < 0.0 {
        x[1] += height;
        x[0] += faces.offset;
        p.velocity[0] += faces.jump;
    }
    p.position = std::array::from_fn(|k| wrap(x[k], sides[k]));
}

impl<const D: usize> SpatialDsmc<D> {
    /// Shears the gas: Lees–Edwards boundaries with the flow u = rate y e_x, the flow added
    /// to every velocity (the gas's velocities become the peculiar ones). None: periodic
    /// again (the flow taken out). Fails in 1D and in a container.
    pub fn set_shear(&mut self, shear: Option<Shear>) -> Result<()> {
        if let Some(s) = &shear {
            Shear::new(s.rate)?;
            if self.tracks.is_some() {
                return Err(crate::tail::shear_while_tracked());
            }
            if D < 2 || self.walls.is_some() || self.gravity.is_some() {
                return Err(Error::out_of_range(
                    "shear",
                    "1D, a container or gravity",
                    "a periodic box of 2 or 3 dimensions",
                ));
            }
        }
        let old = self.shear;
        each!(&mut self.records, records => for p in records.iter_mut() {
            let p = p.body_mut();
            let y = p.position[1];
            if let Some(s) = &old {
                p.velocity[0] -= s.flow(y);
            }
            if let Some(s) = &shear {
                p.velocity[0] += s.flow(y);
            }
        });
        self.shear = shear;
        Ok(())
    }

    /// The sliding faces for a step of `dt` from now, if sheared.
    pub(super) fn sliding_faces(&self, dt: f64) -> Option<Faces> {
        self.shear.map(|s| Faces {
            jump: s.jump(&self.sides),
            offset: s.offset(self.time + dt, &self.sides),
        })
    }

    /// Fills the output system with the particles of all ranks (collective), their lab
    /// velocities or (`peculiar`, under shear) those relative to the flow.
    pub(super) fn fill_system(&mut self, peculiar: bool) {
        with_records!(self, records => self.fill_system_of(&records, peculiar));
    }

    /// [`SpatialDsmc::fill_system`] from `records`, the engine's.
    fn fill_system_of<R: Particle<D>>(&mut self, records: &[R], peculiar: bool) {
        let gathered = (self.comm.size() > 1).then(|| self.gathered(records));
        let shear = if peculiar { self.shear } else { None };
        let s = &mut self.system;
        s.positions.clear();
        s.velocities.clear();
        s.radii.clear();
        s.masses.clear();
        for p in gathered.as_deref().unwrap_or(records) {
            let p = p.body();
            s.positions.push(p.position);
            s.velocities.push(match &shear {
                None => p.velocity,
                Some(shear) => shear.peculiar(p.position[1], &p.velocity),
            });
            s.radii.push(self.species.radii[p.species as usize]);
            s.masses.push(self.species.masses[p.species as usize]);
        }
    }
}
