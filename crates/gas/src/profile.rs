//! Profiles along one axis: the gas cut into slabs of equal width normal to the axis, and
//! in each slab the density, packing fraction, mean velocity and granular temperature
//! (a gas between walls, in gravity or driven from a wall is homogeneous only across the
//! axis).

use crate::system::{ball_volume, System};

/// One slab of a [`profile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slab<const D: usize> {
    /// The slab's centre along the axis.
    pub position: f64,
    /// Particles whose centres lie in the slab.
    pub particles: usize,
    /// Particles per unit volume.
    pub density: f64,
    /// Volume of the particles (by their centres) over the slab's volume.
    pub packing_fraction: f64,
    /// The slab's centre-of-mass velocity u = Σ m v / Σ m (None when empty).
    pub velocity: Option<[f64; D]>,
    /// The temperature of each component, T_k = Σ m (v_k − u_k)² / (n − 1) (None for
    /// fewer than two particles): n − 1 because u is estimated from the same n particles,
    /// which makes E[T_k] = T exactly for any masses when the velocities are independent
    /// with equipartition (E[Σ m c_k²] = n T, E[M u_k²] = T).
    pub temperature: Option<[f64; D]>,
}

impl<const D: usize> Slab<D> {
    /// The granular temperature, the mean of the components' temperatures.
    pub fn temperature(&self) -> Option<f64> {
        self.temperature.map(|t| t.iter().sum::<f64>() / D as f64)
    }
}

/// The profile of `system` along `axis` in `bins` slabs of width L_axis / bins, each particle
/// counted in the slab of its centre; particle numbers and volumes times `weight` (the
/// physical particles a simulated one stands for: `particle_weight` of DSMC, 1 otherwise).
pub fn profile<const D: usize>(
    system: &System<D>,
    axis: usize,
    bins: usize,
    weight: f64,
) -> Vec<Slab<D>> {
    assert!(axis < D && bins > 0, "axis {axis} of {D}, {bins} bins");
    let width = system.sides[axis] / bins as f64;
    let slab_volume = if system.is_cubic() {
        width * system.sides[0].powi(D as i32 - 1)
    } else {
        width * system.volume() / system.sides[axis]
    };
    let slab_of = |x: f64| ((x / width).floor().max(0.0) as usize).min(bins - 1);
    // Per slab: n, Σ m, Σ m v, Σ volume.
    let mut sums = vec![(0usize, 0.0, [0.0; D], 0.0); bins];
    for i in 0..system.len() {
        let s = &mut sums[slab_of(system.positions[i][axis])];
        let m = system.masses[i];
        s.0 += 1;
        s.1 += m;
        for k in 0..D {
            s.2[k] += m * system.velocities[i][k];
        }
        s.3 += ball_volume::<D>(system.radii[i]);
    }
    let velocity: Vec<Option<[f64; D]>> = sums
        .iter()
        .map(|&(n, mass, p, _)| (n > 0).then(|| std::array::from_fn(|k| p[k] / mass)))
        .collect();
    let mut peculiar = vec![[0.0; D]; bins];
    for i in 0..system.len() {
        let b = slab_of(system.positions[i][axis]);
        let u = velocity[b].expect("the slab holds particle i");
        for k in 0..D {
            let c = system.velocities[i][k] - u[k];
            peculiar[b][k] += system.masses[i] * c * c;
        }
    }
    (0..bins)
        .map(|b| {
            let (n, _, _, volume) = sums[b];
            Slab {
                position: (b as f64 + 0.5) * width,
                particles: n,
                density: weight * n as f64 / slab_volume,
                packing_fraction: weight * volume / slab_volume,
                velocity: velocity[b],
                temperature: (n > 1)
                    .then(|| std::array::from_fn(|k| peculiar[b][k] / (n - 1) as f64)),
            }
        })
        .collect()
}

/// The rotation of one slab of a [`rotation_profile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinSlab {
    /// The slab's mean angular velocity ω̄ = Σ I ω / Σ I (None when empty): under shear,
    /// rough particles spin on average with the flow's half vorticity.
    pub angular_velocity: Option<[f64; 3]>,
    /// The rotational temperature about that mean, Σ I |ω − ω̄|² / (d_rot (n − 1)) (None
    /// for fewer than two particles; n − 1 as for the translational temperature of
    /// [`Slab`], with the moments of inertia for the masses).
    pub rotational_temperature: Option<f64>,
}

/// The rotation of the particles of `system` (`rotation`: their inertia factors and
/// angular velocities) in the slabs of [`profile`].
pub fn rotation_profile<const D: usize>(
    system: &System<D>,
    rotation: &crate::rotation::Rotation,
    axis: usize,
    bins: usize,
) -> Vec<SpinSlab> {
    assert!(axis < D && bins > 0, "axis {axis} of {D}, {bins} bins");
    let width = system.sides[axis] / bins as f64;
    let slab_of = |x: f64| ((x / width).floor().max(0.0) as usize).min(bins - 1);
    let moment = |i: usize| rotation.inertia[i] * system.masses[i] * system.radii[i].powi(2);
    // Per slab: n, Σ I, Σ I ω.
    let mut sums = vec![(0usize, 0.0, [0.0; 3]); bins];
    for i in 0..system.len() {
        let s = &mut sums[slab_of(system.positions[i][axis])];
        let moment = moment(i);
        s.0 += 1;
        s.1 += moment;
        for k in 0..3 {
            s.2[k] += moment * rotation.angular[i][k];
        }
    }
    let mean: Vec<[f64; 3]> = sums
        .iter()
        .map(|&(_, total, l)| std::array::from_fn(|k| l[k] / total))
        .collect();
    let mut spread = vec![0.0; bins];
    for i in 0..system.len() {
        let b = slab_of(system.positions[i][axis]);
        let w = &rotation.angular[i];
        spread[b] += moment(i) * (0..3).map(|k| (w[k] - mean[b][k]).powi(2)).sum::<f64>();
    }
    let d_rot = crate::rotation::rotational_dimension(D) as f64;
    (0..bins)
        .map(|b| {
            let n = sums[b].0;
            SpinSlab {
                angular_velocity: (n > 0).then_some(mean[b]),
                rotational_temperature: (n > 1).then(|| spread[b] / (d_rot * (n - 1) as f64)),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Oracle: slabs counted by hand for four particles placed by hand.
    #[test]
    fn slabs_by_hand() {
        let system = System::<2> {
            sides: [4.0; 2],
            positions: vec![[0.5, 0.1], [1.0, 0.2], [3.0, 3.9], [3.5, 3.99]],
            velocities: vec![[1.0, 0.0], [-1.0, 2.0], [0.0, 0.0], [0.0, 0.0]],
            radii: vec![0.5; 4],
            masses: vec![1.0, 3.0, 1.0, 1.0],
        };
        let slabs = profile(&system, 1, 2, 1.0);
        assert_eq!(slabs[0].particles, 2);
        assert_eq!(slabs[0].position, 1.0);
        assert_eq!(slabs[0].density, 2.0 / 8.0);
        let disc = std::f64::consts::PI * 0.25;
        assert!((slabs[0].packing_fraction - 2.0 * disc / 8.0).abs() < 1e-15);
        // u = (1 - 3, 6) / 4; T_x = (1 (1.5)^2 + 3 (0.5)^2) / 1, T_y = (1 (1.5)^2 + 3 (0.5)^2).
        assert_eq!(slabs[0].velocity, Some([-0.5, 1.5]));
        assert_eq!(slabs[0].temperature, Some([3.0, 3.0]));
        assert_eq!(slabs[1].temperature, Some([0.0, 0.0]));
        assert_eq!(slabs[1].position, 3.0);
        let one = profile(&system, 0, 4, 2.0);
        assert_eq!(one[2].particles, 0);
        assert_eq!(one[2].velocity, None);
        assert_eq!(one[0].temperature, None);
        assert_eq!(one[0].density, 2.0 / 4.0);
    }

    /// Oracle: the spins of three disks and a sphere's by hand.
    #[test]
    fn spins_by_hand() {
        let system = System::<2> {
            sides: [4.0; 2],
            positions: vec![[0.5, 0.1], [1.0, 0.2], [3.0, 3.0], [3.5, 3.99]],
            velocities: vec![[0.0; 2]; 4],
            radii: vec![0.5, 0.5, 1.0, 0.5],
            masses: vec![1.0, 1.0, 2.0, 1.0],
        };
        let mut rotation = crate::rotation::Rotation::at_rest(4, 0.5);
        rotation.angular = vec![[0.0, 0.0, 1.0], [0.0, 0.0, 3.0], [0.0, 0.0, 2.0], [0.0; 3]];
        // Slab 0: I = 0.125 each, mean 2, T_rot = 0.125 (1 + 1) / (1 * 1) = 0.25.
        // Slab 1: a disk of I = 1 (w = 2) and one at rest of I = 0.125: mean m = 2 / 1.125,
        // T_rot = (1 (2 - m)^2 + 0.125 m^2) / 1.
        let slabs = rotation_profile(&system, &rotation, 1, 2);
        assert_eq!(slabs[0].angular_velocity, Some([0.0, 0.0, 2.0]));
        assert_eq!(slabs[0].rotational_temperature, Some(0.25));
        let m = 2.0 / 1.125;
        let t = (2.0 - m) * (2.0 - m) + 0.125 * m * m;
        assert!((slabs[1].rotational_temperature.unwrap() - t).abs() < 1e-15);
        let one = rotation_profile(&system, &rotation, 0, 4);
        assert_eq!(one[2].angular_velocity, None);
        assert_eq!(one[3].rotational_temperature, Some(t));
    }
}
