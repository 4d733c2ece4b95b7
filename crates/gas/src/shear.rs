//! Uniform shear flow (USF) and the stress it is measured by.
//!
//! The flow u = a y e_x (flow along x, gradient along y) is imposed by Lees–Edwards
//! boundaries (Lees & Edwards, J. Phys. C 5, 1921 (1972)): the periodic images of the box
//! above and below it slide along x with the velocity ± a L_y, so the image of a sphere at
//! (x, y) with velocity v seen across the upper face of the box is at
//! (x + δ(t), y + L_y) with velocity v + a L_y e_x, where δ(t) = a L_y t (modulo L_x) is the
//! images' offset. A sphere that leaves through that face comes back through the lower one
//! as its image: x − δ, y − L_y, v_x − a L_y. In a spatially homogeneous description (the
//! homogeneous DSMC) the same state is the USF in the frame moving with the flow: the
//! peculiar velocities V = v − a y e_x obey dV_x/dt = −a V_y between collisions
//! (Brey, Ruiz-Montero & Moreno, Phys. Rev. E 55, 2846 (1997); Garzó & Santos, *Kinetic
//! Theory of Gases in Shear Flows*, Kluwer 2003, Ch. 2).
//!
//! The pressure tensor P = P^k + P^c is the kinetic part Σ m V V / V_box of the peculiar
//! velocities plus the collisional transfer: each collision moves the momentum J n (J the
//! impulse, n the unit vector from one centre to the other, σ their distance) across σ n,
//! and P^c = Σ J σ n n / (V_box Δt) over the collisions of a time Δt (Allen & Tildesley,
//! *Computer Simulation of Liquids*, Sec. 2.4; its trace / D is the virial pressure of
//! [`crate::observe::pressure`]). [`Virial`] sums J σ n n.

use crate::error::{Error, Result};
use crate::system::Vector;
use serde::{Deserialize, Serialize};

/// The uniform shear flow u = rate · y e_x.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shear {
    pub rate: f64,
}

impl Shear {
    /// Fails, naming `rate`, unless the rate is finite and not 0.
    pub fn new(rate: f64) -> Result<Self> {
        if !(rate.is_finite() && rate != 0.0) {
            return Err(Error::out_of_range("rate", rate, "finite and not 0"));
        }
        Ok(Shear { rate })
    }

    /// Fails unless an engine of dimension D can impose this shear: the rate as in
    /// [`Shear::new`], and (`shear`) D of at least 2 (the gradient is along y).
    pub fn check_for<const D: usize>(&self) -> Result<()> {
        Shear::new(self.rate)?;
        if D < 2 {
            return Err(Error::out_of_range(
                "shear",
                "1 dimension",
                "2 or 3 dimensions (the gradient is along y)",
            ));
        }
        Ok(())
    }

    /// The flow velocity along x at height y.
    #[inline]
    pub fn flow(&self, y: f64) -> f64 {
        self.rate * y
    }

    /// The offset δ(t) = a L_y t of the images above the box, in [0, L_x).
    pub fn offset(&self, time: f64, sides: &[f64]) -> f64 {
        (self.rate * sides[1] * time).rem_euclid(sides[0])
    }

    /// The velocity difference a L_y between the images above the box and the box.
    #[inline]
    pub fn jump(&self, sides: &[f64]) -> f64 {
        self.rate * sides[1]
    }

    /// The peculiar velocity of a sphere at height y with (lab) velocity v.
    #[inline]
    pub fn peculiar<const D: usize>(&self, y: f64, v: &Vector<D>) -> Vector<D> {
        let mut u = *v;
        u[0] -= self.flow(y);
        u
    }
}

/// The index of the component (a, b), a <= b, of a symmetric tensor stored as
/// xx, yy, zz, xy, xz, yz (2D: zz, xz, yz stay 0).
#[inline]
pub const fn component(a: usize, b: usize) -> usize {
    let (a, b) = if a <= b { (a, b) } else { (b, a) };
    if a == b {
        a
    } else {
        a + b + 2
    }
}

/// The collisional momentum transfer summed over collisions: Σ J σ n_a n_b (J the impulse,
/// σ the distance of the centres, n their unit vector), as xx, yy, zz, xy, xz, yz. Its
/// trace is [`crate::Counters::virial`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Virial(pub [f64; 6]);

impl Virial {
    /// Adds a collision of impulse `impulse` across `distance` along the unit vector `n`.
    #[inline(always)]
    pub fn add<const D: usize>(&mut self, impulse: f64, distance: f64, n: &Vector<D>) {
        let w = impulse * distance;
        for a in 0..D {
            for b in a..D {
                self.0[component(a, b)] += w * n[a] * n[b];
            }
        }
    }

    /// Adds the tangential part of a rough collision: momentum `to_j` given to the
    /// partner at `distance` along `n`, symmetrized (r_a P_b + r_b P_a) / 2 (the
    /// antisymmetric part is the couple the spins take; the stress is its symmetric part).
    #[inline]
    pub fn add_tangential<const D: usize>(
        &mut self,
        distance: f64,
        n: &Vector<D>,
        to_j: &[f64; 3],
    ) {
        for a in 0..D {
            for b in a..D {
                self.0[component(a, b)] += 0.5 * distance * (n[a] * to_j[b] + n[b] * to_j[a]);
            }
        }
    }

    /// Adds another sum (a block's, a cell's).
    pub fn merge(&mut self, other: &Virial) {
        for (s, o) in self.0.iter_mut().zip(other.0) {
            *s += o;
        }
    }

    /// The sum since `earlier`.
    pub fn since(&self, earlier: &Virial) -> Virial {
        Virial(std::array::from_fn(|c| self.0[c] - earlier.0[c]))
    }

    /// The component (a, b).
    pub fn get(&self, a: usize, b: usize) -> f64 {
        self.0[component(a, b)]
    }

    /// Checks a restored sum: finite.
    pub fn check(&self) -> Result<()> {
        if self.0.iter().all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(Error::out_of_range(
                "virial",
                format!("{:?}", self.0),
                "finite sums",
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tensor's trace is the scalar virial J σ; the components are those of n n.
    #[test]
    fn the_virial_tensor_traces_to_the_scalar_virial() {
        let mut v = Virial::default();
        let n = [0.6, 0.0, 0.8];
        v.add::<3>(2.0, 1.5, &n);
        let trace = v.get(0, 0) + v.get(1, 1) + v.get(2, 2);
        assert!((trace - 3.0).abs() < 1e-15);
        assert!((v.get(0, 2) - 3.0 * 0.48).abs() < 1e-15);
        assert_eq!(v.get(2, 0), v.get(0, 2));
        assert_eq!(v.get(0, 1), 0.0);
        assert_eq!(component(0, 1), 3);
        assert_eq!(component(0, 2), 4);
        assert_eq!(component(1, 2), 5);
    }

    #[test]
    fn the_offset_stays_in_the_box() {
        let shear = Shear::new(-0.3).unwrap();
        let sides = [10.0, 20.0];
        for t in [0.0, 1.0, 7.3, 1e6] {
            let d = shear.offset(t, &sides);
            assert!((0.0..10.0).contains(&d), "{d}");
        }
        assert!((shear.offset(1.0, &sides) - 4.0).abs() < 1e-12);
        assert!(Shear::new(f64::NAN).is_err());
        assert!(Shear::new(0.0).is_err());
    }
}
