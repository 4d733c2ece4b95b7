//! The state: positions, velocities, radii and masses of N spheres in a periodic box, and
//! the geometry of the box.

use serde::{Deserialize, Serialize};

/// A vector in D dimensions.
pub type Vector<const D: usize> = [f64; D];

/// N smooth spheres in the periodic box [0, L_1) x ... x [0, L_D). Serialized with each
/// vector a list of D numbers (the box as one number when it is a cube:
/// [`crate::serde_util::box_sides`]); a state read from outside is checked with
/// [`System::check`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct System<const D: usize> {
    /// Sides of the periodic box, one per axis.
    #[serde(rename = "length", with = "crate::serde_util::box_sides")]
    pub sides: Vector<D>,
    #[serde(with = "crate::serde_util::vectors")]
    pub positions: Vec<Vector<D>>,
    #[serde(with = "crate::serde_util::vectors")]
    pub velocities: Vec<Vector<D>>,
    pub radii: Vec<f64>,
    pub masses: Vec<f64>,
}

impl<const D: usize> System<D> {
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Volume (or area, length) of the box.
    pub fn volume(&self) -> f64 {
        box_volume(&self.sides)
    }

    /// Whether the box is a cube (every side the same).
    pub fn is_cubic(&self) -> bool {
        is_cube(&self.sides)
    }

    /// The shortest side of the box.
    pub fn shortest_side(&self) -> f64 {
        self.sides.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// The minimum-image separation b - a.
    pub fn separation(&self, a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
        std::array::from_fn(|k| minimum_image(b[k] - a[k], self.sides[k]))
    }

    /// Position x wrapped into the box.
    pub fn wrapped(&self, x: &Vector<D>) -> Vector<D> {
        std::array::from_fn(|k| wrap(x[k], self.sides[k]))
    }

    /// Checks a state read from outside (a check-point): finite box sides > 0, radii and
    /// masses finite and > 0, finite velocities, and (if `in_box`) positions in the box.
    pub fn check(&self, in_box: bool) -> crate::Result<()> {
        use crate::Error;
        for (k, &side) in self.sides.iter().enumerate() {
            let name = if self.is_cubic() {
                "length".to_string()
            } else {
                format!("sides[{k}]")
            };
            crate::error::require_positive(&name, side)?;
        }
        let n = self.positions.len();
        if [self.velocities.len(), self.radii.len(), self.masses.len()] != [n; 3] {
            return Err(Error::LengthMismatch {
                what: "positions, velocities, radii and masses".into(),
            });
        }
        for (what, list) in [("radii", &self.radii), ("masses", &self.masses)] {
            if let Some(i) = list.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
                return Err(Error::out_of_range(
                    format!("{what}[{i}]"),
                    list[i],
                    "a finite number > 0",
                ));
            }
        }
        if let Some(index) = self
            .velocities
            .iter()
            .position(|v| v.iter().any(|x| !x.is_finite()))
        {
            return Err(Error::NotFinite {
                what: "velocities",
                index,
            });
        }
        let energy = crate::observe::kinetic_energy(self);
        if !energy.is_finite() {
            return Err(Error::out_of_range(
                "velocities",
                "a kinetic energy beyond the range of f64",
                "a finite energy",
            ));
        }
        // The observers' Sonine coefficient sums (m c^2)^2: a finite energy is not enough.
        if !crate::observe::fourth_moment_sum(self).is_finite() {
            return Err(Error::out_of_range(
                "velocities",
                "a fourth moment beyond the range of f64",
                "speeds whose fourth powers sum to a finite number",
            ));
        }
        let sides = self.sides;
        if let Some(i) = self.positions.iter().position(|p| {
            p.iter()
                .zip(&sides)
                .any(|(x, &l)| !(x.is_finite() && (!in_box || (0.0..l).contains(x))))
        }) {
            return Err(Error::out_of_range(
                format!("positions[{i}]"),
                format!("{:?}", self.positions[i]),
                format!("finite coordinates in the box [0, L) per side, L = {sides:?}"),
            ));
        }
        Ok(())
    }

    /// Fraction of the volume occupied by the spheres.
    pub fn packing_fraction(&self) -> f64 {
        self.radii.iter().map(|&r| ball_volume::<D>(r)).sum::<f64>() / self.volume()
    }
}

/// The side of the periodic box in which spheres of total volume `sphere_volume` fill the
/// packing fraction `phi`: (sphere_volume / phi)^(1/D). The one place this is computed.
pub fn box_side<const D: usize>(sphere_volume: f64, phi: f64) -> f64 {
    (sphere_volume / phi).powf(1.0 / D as f64)
}

/// A box given by one side (a cube) or by its D sides.
pub trait IntoSides<const D: usize> {
    fn into_sides(self) -> Vector<D>;
}

impl<const D: usize> IntoSides<D> for f64 {
    fn into_sides(self) -> Vector<D> {
        [self; D]
    }
}

impl<const D: usize> IntoSides<D> for Vector<D> {
    fn into_sides(self) -> Vector<D> {
        self
    }
}

/// The volume (area, length) of a box with these sides.
pub fn box_volume<const D: usize>(sides: &Vector<D>) -> f64 {
    if is_cube(sides) {
        // As the cube always computed it: L^D.
        sides[0].powi(D as i32)
    } else {
        sides.iter().product()
    }
}

/// Whether every side is the same.
pub fn is_cube<const D: usize>(sides: &Vector<D>) -> bool {
    sides.iter().all(|&l| l == sides[0])
}

/// The box side of `n` equal spheres of diameter `diameter` at packing fraction `phi`.
pub fn monodisperse_box_side<const D: usize>(n: usize, diameter: f64, phi: f64) -> f64 {
    box_side::<D>(n as f64 * ball_volume::<D>(0.5 * diameter), phi)
}

/// x wrapped into [-L/2, L/2].
#[inline]
pub fn minimum_image(x: f64, length: f64) -> f64 {
    minimum_image_within(x, length, 0.5 * length)
}

/// [`minimum_image`] with the half side `half` = L / 2 given (computed once for a loop).
#[inline]
pub fn minimum_image_within(x: f64, length: f64, half: f64) -> f64 {
    // Comparisons first: round() is a library call on baseline x86-64.
    if (-half..=half).contains(&x) {
        x
    } else {
        x - length * (x / length).round()
    }
}

/// x wrapped into [0, L).
#[inline]
pub fn wrap(x: f64, length: f64) -> f64 {
    if (0.0..length).contains(&x) {
        return x;
    }
    let y = x - length * (x / length).floor();
    if y >= length {
        0.0
    } else {
        y
    }
}

/// [`wrap`] for an x that is mostly outside [0, L) (the sliding cells' offsets u t):
/// the same bits, without the library call of `f64::floor` ([`floor_of`]). Not used by
/// [`wrap`] itself: its out-of-line body made the streaming loops of spatial DSMC decline
/// to inline their closure (+6 % instructions, measured with callgrind).
#[inline]
pub fn wrap_far(x: f64, length: f64) -> f64 {
    if (0.0..length).contains(&x) {
        return x;
    }
    let y = x - length * floor_of(x / length);
    if y >= length {
        0.0
    } else {
        y
    }
}

/// floor(q), without the library call `f64::floor` is on baseline x86-64 (no SSE4.1):
/// truncation by conversion to an integer (one instruction), one step down for a
/// negative q with a fraction. Exact, hence the same bits as `f64::floor`, for |q| < 2^63
/// but q = -0.0 (+0.0 here; [`wrap_far`] never asks for it); beyond, and for NaN,
/// `f64::floor` itself.
#[inline]
fn floor_of(q: f64) -> f64 {
    const LIMIT: f64 = 9.223372036854775e18;
    if !(-LIMIT..LIMIT).contains(&q) {
        return q.floor();
    }
    let t = q as i64 as f64;
    if t > q {
        t - 1.0
    } else {
        t
    }
}

/// Volume of a D-ball of radius r.
pub fn ball_volume<const D: usize>(r: f64) -> f64 {
    match D {
        1 => 2.0 * r,
        2 => std::f64::consts::PI * r * r,
        3 => 4.0 / 3.0 * std::f64::consts::PI * r * r * r,
        _ => panic!("dimension {D} is not supported (1, 2, 3)"),
    }
}

#[inline]
pub fn dot<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod floor_tests {
    use super::{floor_of, wrap, wrap_far};
    use rand::{Rng, SeedableRng};

    /// `floor_of` is `f64::floor` bit for bit (all but -0.0), across scales and at the
    /// integers and their neighbours; `wrap_far` therefore gives the bits of `wrap`.
    #[test]
    fn floor_of_is_the_library_floor() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let mut cases = vec![
            0.0, 0.5, -0.5, 1.0, -1.0, 2.5, -2.5, 1e18, -1e18, 9.3e18, -9.3e18,
        ];
        cases.extend([f64::INFINITY, f64::NEG_INFINITY, f64::MAX, f64::MIN]);
        for _ in 0..100_000 {
            let scale = 10f64.powi(rng.random_range(-3..20));
            let q: f64 = rng.random_range(-1.0..1.0) * scale;
            cases.extend([q, q.floor(), q.floor().next_up(), q.floor().next_down()]);
        }
        for q in cases {
            assert_eq!(floor_of(q).to_bits(), q.floor().to_bits(), "{q}");
        }
        assert!(floor_of(f64::NAN).is_nan());
        for _ in 0..100_000 {
            let length: f64 = rng.random_range(0.1..100.0);
            let x: f64 = rng.random_range(-1e6..1e6);
            assert_eq!(
                wrap_far(x, length).to_bits(),
                wrap(x, length).to_bits(),
                "{x} {length}"
            );
        }
    }
}
