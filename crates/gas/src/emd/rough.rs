//! Rough spheres in the event-driven engine: the particles' rotation (kept beside the
//! particle records, which a collision alone reads it from: free flight leaves angular
//! velocities and contact times alone) and the tangential half of a collision
//! (`crate::rotation::tangential_kick`, after the normal impulse of the smooth rule).
//! Walls are smooth (no torque), the thermostats heat translation only, and a collision
//! the TC model makes elastic is smooth as well.

use super::{EventDriven, Particle};
use crate::error::{Error, Result};
use crate::rotation::{tangential_kick, Contact, Rotation};
use crate::system::Vector;
use restitution::rough::Body;

impl<const D: usize> EventDriven<D> {
    /// Gives the spheres `rotation` (checked: one entry per sphere, inertia factors in
    /// range, disks about z), or takes it away — refused while the law is rough.
    pub fn set_rotation(&mut self, rotation: Option<Rotation>) -> Result<()> {
        match rotation {
            Some(r) => {
                r.check(self.particles.len(), D)?;
                self.rotation = Some(r);
            }
            None if self.tangential.is_some() => {
                return Err(Error::out_of_range(
                    "rotation",
                    "none",
                    "a rotation for every sphere: the law is rough",
                ))
            }
            None => self.rotation = None,
        }
        Ok(())
    }

    /// The tangential impulse of the collision of i and j just given its normal impulse
    /// `normal_impulse` along `n`, `distance` apart (`jump`: the velocity of j's image
    /// less j's along x, across a sheared face).
    pub(super) fn rough_kick(
        &mut self,
        (i, j): (usize, usize),
        n: &Vector<D>,
        distance: f64,
        normal_impulse: f64,
        jump: f64,
    ) {
        let (Some(rule), Some(rotation)) = (&self.tangential, &mut self.rotation) else {
            return;
        };
        let rule = match &self.tangential_pairs {
            None => rule,
            Some((table, kinds)) => table.rule(kinds[i] as usize, kinds[j] as usize),
        };
        let (mut a, mut b) = (self.particles[i], self.particles[j]);
        let mut relative: Vector<D> = std::array::from_fn(|k| a.velocity[k] - b.velocity[k]);
        relative[0] -= jump;
        let (mut wa, mut wb) = (rotation.angular[i], rotation.angular[j]);
        let body = |p: &Particle<D>, q: f64| Body {
            mass: p.mass,
            radius: p.radius,
            inertia: q,
        };
        let contact = Contact::new(
            rule,
            body(&a, rotation.inertia[i]),
            body(&b, rotation.inertia[j]),
        );
        let kick = tangential_kick(
            &contact,
            n,
            &relative,
            normal_impulse.abs(),
            (&mut a.velocity, &mut wa),
            (&mut b.velocity, &mut wb),
        );
        self.particles[i].velocity = a.velocity;
        self.particles[j].velocity = b.velocity;
        rotation.angular[i] = wa;
        rotation.angular[j] = wb;
        rotation.sliding += kick.sliding as u64;
        self.tally.energy_lost += kick.energy_lost;
        if let Some(virial) = &mut self.virial {
            virial.add_tangential(distance, n, &kick.to_j);
        }
    }
}

/// The tangential rules per pair of kinds of a law that has them, and each particle's
/// kind (by its radius and mass); fails for a particle of no kind.
pub(super) fn kinds_of<const D: usize>(
    law: &dyn restitution::Restitution,
    particles: &[Particle<D>],
) -> Result<Option<(restitution::rough::TangentialPairs, Vec<u16>)>> {
    let Some(table) = law.tangential_pairs() else {
        return Ok(None);
    };
    let kinds = particles
        .iter()
        .map(|p| {
            table
                .kind_of(p.radius, p.mass)
                .map(|k| k as u16)
                .ok_or_else(|| {
                    Error::out_of_range(
                        "tangential_restitution",
                        format!(
                            "no rule for particles of radius {} and mass {}",
                            p.radius, p.mass
                        ),
                        "a rule for every pair of species",
                    )
                })
        })
        .collect::<Result<Vec<u16>>>()?;
    Ok(Some((table.clone(), kinds)))
}
