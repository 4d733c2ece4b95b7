//! The state: positions, velocities, radii and masses of N spheres in a periodic box.

/// A vector in D dimensions.
pub type Vector<const D: usize> = [f64; D];

/// N smooth spheres in the periodic box [0, L)^D.
#[derive(Debug, Clone, PartialEq)]
pub struct System<const D: usize> {
    /// Side of the periodic box.
    pub length: f64,
    pub positions: Vec<Vector<D>>,
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
        self.length.powi(D as i32)
    }

    /// The minimum-image separation b - a.
    pub fn separation(&self, a: &Vector<D>, b: &Vector<D>) -> Vector<D> {
        std::array::from_fn(|k| minimum_image(b[k] - a[k], self.length))
    }

    /// Fraction of the volume occupied by the spheres.
    pub fn packing_fraction(&self) -> f64 {
        self.radii.iter().map(|&r| ball_volume::<D>(r)).sum::<f64>() / self.volume()
    }
}

/// x wrapped into [-L/2, L/2].
#[inline]
pub fn minimum_image(x: f64, length: f64) -> f64 {
    // Comparisons first: round() is a library call on baseline x86-64.
    let half = 0.5 * length;
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
