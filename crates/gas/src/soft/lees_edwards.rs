//! Lees–Edwards boundaries in soft-sphere MD (uniform shear flow u = a y e_x; see
//! [`crate::shear`]; Lees & Edwards, J. Phys. C 5, 1921 (1972); Allen & Tildesley,
//! *Computer Simulation of Liquids*, Sec. 11.3).
//!
//! Velocities are the lab frame's, so the velocity-Verlet step is the periodic box's. The
//! images above the box sit at x + δ(t), y + L_y and move with v + a L_y e_x,
//! δ(t) = a L_y t mod L_x. A pair whose y separation exceeds L_y / 2 is a pair across a face:
//! the second sphere is taken as its image on the first's side (x_j ∓ δ, y_j ∓ L_y,
//! v_j ∓ a L_y e_x), so that the overlap, its rate (the damping of Eq. (2) of Müller &
//! Pöschel 2011) and the pair's virial are those of the nearest image. A sphere that leaves
//! through the top face re-enters through the bottom one as its image (x − δ, y − L_y,
//! v_x − a L_y), and the reverse: its peculiar velocity V = v − a y e_x is unchanged.
//!
//! Neighbour lists: the rows of cells at the faces are paired with the columns of the row
//! across that their images overlap, and the image's slide counts like a displacement in
//! the skin criterion (a pair across a face approaches by at most the two spheres' flights
//! plus |a| L_y per unit time; [`super::neighbors::NeighborList::sheared`]).

use super::SoftSphere;
use crate::error::{Error, Result};
use crate::shear::Shear;
use crate::system::{minimum_image, wrap, Vector};

/// The sliding images at one time: what a pair across a face needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Images {
    /// δ(t), in [0, L_x).
    pub delta: f64,
    /// a L_y: the velocity of the images above relative to the box.
    pub jump: f64,
}

impl Images {
    /// The images of `shear` at time `t` in a box of `sides`.
    #[inline]
    pub fn at(shear: &Shear, t: f64, sides: &[f64]) -> Self {
        Images {
            delta: shear.offset(t, sides),
            jump: shear.jump(sides),
        }
    }

    /// r = x_j' − x_i with x_j' the image of j nearest to i (positions in the box), and s:
    /// the image is (x_j + s δ, y_j + s L_y) with velocity v_j + s a L_y e_x (s = −1 for j
    /// across the top face seen from the bottom, +1 the reverse, 0 within the box).
    #[inline(always)]
    pub fn separation<const D: usize>(
        &self,
        xi: &Vector<D>,
        xj: &Vector<D>,
        sides: &Vector<D>,
    ) -> (Vector<D>, f64) {
        let dy = xj[1] - xi[1];
        let s = if dy > 0.5 * sides[1] {
            -1.0
        } else if dy < -0.5 * sides[1] {
            1.0
        } else {
            0.0
        };
        let r = std::array::from_fn(|k| match k {
            0 => minimum_image(xj[0] + s * self.delta - xi[0], sides[0]),
            1 => dy + s * sides[1],
            _ => minimum_image(xj[k] - xi[k], sides[k]),
        });
        (r, s)
    }
}

impl<const D: usize> SoftSphere<D> {
    /// Shears the gas: Lees–Edwards boundaries with the flow u = rate y e_x (flow along x,
    /// gradient along y), the flow added to every velocity (the gas's velocities taken as
    /// the peculiar ones) and the forces computed anew. None: periodic again (the flow
    /// taken out). Fails in 1D, in a container (walls, gravity), and (`rate`) for a rate
    /// that is not finite and nonzero.
    pub fn set_shear(&mut self, shear: Option<Shear>) -> Result<()> {
        if let Some(s) = &shear {
            s.check_for::<D>()?;
            if self.tracks.is_some() {
                return Err(crate::tail::shear_while_tracked());
            }
            if self.container.is_some() || self.saved_container.is_some() {
                return Err(Error::out_of_range(
                    "shear",
                    "a container or gravity",
                    "a periodic box (Lees-Edwards boundaries on x and y)",
                ));
            }
        }
        let old = self.shear;
        for (x, v) in self
            .system
            .positions
            .iter()
            .zip(&mut self.system.velocities)
        {
            if let Some(s) = &old {
                v[0] -= s.flow(x[1]);
            }
            if let Some(s) = &shear {
                v[0] += s.flow(x[1]);
            }
        }
        self.shear = shear;
        self.neighbors
            .sheared(shear.map(|s| s.jump(&self.system.sides)));
        self.refresh_forces();
        Ok(())
    }

    /// The shear flow, if the gas is sheared.
    pub fn shear(&self) -> Option<Shear> {
        self.shear
    }

    /// The sliding images at time `t`, if sheared.
    #[inline]
    pub(super) fn images_at(&self, t: f64) -> Option<Images> {
        self.shear
            .as_ref()
            .map(|s| Images::at(s, t, &self.system.sides))
    }

    /// x = x + dt v for every sphere, wrapped along x (and z); a sphere that leaves through
    /// the top or bottom face re-enters as its image at the time t + dt of the new positions
    /// (module documentation), its new speed told to the neighbour list.
    pub(super) fn drift_sheared(&mut self, dt: f64) {
        let Some(shear) = self.shear else {
            return;
        };
        let sides = self.system.sides;
        let Images { delta, jump } = Images::at(&shear, self.time + dt, &sides);
        let height = sides[1];
        let s = &mut self.system;
        for (x, v) in s.positions.iter_mut().zip(&mut s.velocities) {
            for k in 0..D {
                x[k] += dt * v[k];
                if k != 1 {
                    x[k] = wrap(x[k], sides[k]);
                }
            }
            let sign = if x[1] >= height {
                -1.0
            } else if x[1] < 0.0 {
                1.0
            } else {
                continue;
            };
            x[0] = wrap(x[0] + sign * delta, sides[0]);
            x[1] += sign * height;
            // -tiny + L_y may round to L_y, which a wrap would take to 0 without the shift.
            if x[1] >= height {
                x[1] = height * (1.0 - f64::EPSILON);
            }
            v[0] += sign * jump;
            self.neighbors.kicked(v);
        }
    }

    /// Fills `view` with the state whose velocities are the peculiar ones (under shear).
    pub(super) fn fill_view(&mut self, shear: Shear) {
        let (s, view) = (&self.system, &mut self.view);
        view.sides = s.sides;
        view.positions.clone_from(&s.positions);
        view.radii.clone_from(&s.radii);
        view.masses.clone_from(&s.masses);
        view.velocities.clear();
        view.velocities.extend(
            s.positions
                .iter()
                .zip(&s.velocities)
                .map(|(x, v)| shear.peculiar(x[1], v)),
        );
    }
}
