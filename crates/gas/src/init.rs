//! Initial states: non-overlapping random positions at a given packing fraction and
//! Maxwellian velocities at a given temperature with zero total momentum.

use crate::cells::CellGrid;
use crate::system::{ball_volume, dot, System, Vector};
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_pcg::Pcg64;

/// Packing fraction up to which positions are placed by random sequential addition; above
/// it on a lattice, melted by elastic collisions ([`melt`]).
pub const RANDOM_ADDITION_LIMIT: f64 = 0.3;

/// A monodisperse gas: `n` spheres of diameter `diameter` and mass `mass` at packing
/// fraction `phi`, temperature `temperature` (T = m <v^2> / D), all fixed by `seed`.
pub fn monodisperse<const D: usize>(
    n: usize,
    phi: f64,
    diameter: f64,
    mass: f64,
    temperature: f64,
    seed: u64,
) -> Result<System<D>, String> {
    if n < 2 {
        return Err(format!("particles = {n}: need at least 2"));
    }
    if !(phi > 0.0 && phi <= max_packing::<D>()) {
        return Err(format!(
            "packing_fraction = {phi}: allowed 0 < phi <= {}",
            max_packing::<D>()
        ));
    }
    let length = (n as f64 * ball_volume::<D>(0.5 * diameter) / phi).powf(1.0 / D as f64);
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut positions = if phi <= RANDOM_ADDITION_LIMIT {
        random_addition::<D>(n, length, diameter, &mut rng)?
    } else {
        lattice::<D>(n, length, diameter)?
    };
    sort_by_space(&mut positions, length, diameter);
    let velocities = maxwellian::<D>(n, mass, temperature, &mut rng);
    let system = System {
        length,
        positions,
        velocities,
        radii: vec![0.5 * diameter; n],
        masses: vec![mass; n],
    };
    if phi <= RANDOM_ADDITION_LIMIT {
        Ok(system)
    } else {
        melt(system, MELTING_COLLISIONS_PER_PARTICLE)
    }
}

/// Elastic collisions per particle that melt the lattice of a dense initial state.
pub const MELTING_COLLISIONS_PER_PARTICLE: u64 = 10;

/// Runs elastic event-driven MD for `per_particle` collisions per particle (energy and
/// momentum are conserved exactly up to round-off, so T stays the initial temperature)
/// and returns the state: the lattice order is gone, the velocities are Maxwellian.
pub fn melt<const D: usize>(system: System<D>, per_particle: u64) -> Result<System<D>, String> {
    let n = system.len() as u64;
    let elastic = restitution::Constant::new(1.0).map_err(|e| e.to_string())?;
    let mut engine = crate::EventDriven::new(system, Box::new(elastic))?;
    engine.run_collisions(per_particle * n / 2);
    Ok(engine.system().clone())
}

/// Packing fractions the initializer accepts.
pub fn max_packing<const D: usize>() -> f64 {
    match D {
        1 => 0.9,
        2 => 0.7,
        _ => 0.45,
    }
}

fn random_addition<const D: usize>(
    n: usize,
    length: f64,
    diameter: f64,
    rng: &mut Pcg64,
) -> Result<Vec<Vector<D>>, String> {
    let mut grid = CellGrid::<D>::new(length, diameter, n);
    let mut positions: Vec<Vector<D>> = Vec::with_capacity(n);
    let system = System::<D> {
        length,
        positions: vec![],
        velocities: vec![],
        radii: vec![],
        masses: vec![],
    };
    for i in 0..n {
        let mut placed = false;
        for _ in 0..100_000 {
            let p: Vector<D> = std::array::from_fn(|_| rng.random::<f64>() * length);
            let c = grid.coords_of(&p);
            let mut free = true;
            grid.for_each_neighbor(&c, |j| {
                let d = system.separation(&p, &positions[j]);
                free &= dot(&d, &d) >= diameter * diameter;
            });
            if free {
                positions.push(p);
                grid.insert(i, c);
                placed = true;
                break;
            }
        }
        if !placed {
            return Err(format!("could not place particle {i} by random addition"));
        }
    }
    Ok(positions)
}

fn lattice<const D: usize>(n: usize, length: f64, diameter: f64) -> Result<Vec<Vector<D>>, String> {
    let side = (n as f64).powf(1.0 / D as f64).ceil() as usize;
    let spacing = length / side as f64;
    if spacing < diameter {
        return Err(format!("packing fraction too high for a simple lattice (spacing {spacing} < diameter {diameter})"));
    }
    Ok((0..n)
        .map(|i| {
            let mut rest = i;
            std::array::from_fn(|_| {
                let k = rest % side;
                rest /= side;
                (k as f64 + 0.5) * spacing
            })
        })
        .collect())
}

/// Gaussian velocities with zero mean, rescaled so that m <v^2> / D = temperature exactly.
fn maxwellian<const D: usize>(
    n: usize,
    mass: f64,
    temperature: f64,
    rng: &mut Pcg64,
) -> Vec<Vector<D>> {
    let mut v: Vec<Vector<D>> = (0..n)
        .map(|_| std::array::from_fn(|_| rng.sample::<f64, _>(StandardNormal)))
        .collect();
    let mean: Vector<D> = std::array::from_fn(|k| v.iter().map(|x| x[k]).sum::<f64>() / n as f64);
    for x in &mut v {
        for k in 0..D {
            x[k] -= mean[k];
        }
    }
    let current = mass * v.iter().map(|x| dot(x, x)).sum::<f64>() / (n * D) as f64;
    let scale = (temperature / current).sqrt();
    for x in &mut v {
        for c in x.iter_mut() {
            *c *= scale;
        }
    }
    v
}

/// Orders particles along a Morton (Z-order) curve of cells one diameter wide, so that
/// neighbours in space are neighbours in memory (fewer cache misses in large systems).
fn sort_by_space<const D: usize>(positions: &mut [Vector<D>], length: f64, diameter: f64) {
    let cells = (length / diameter).floor().max(1.0);
    let key = |p: &Vector<D>| -> u64 {
        let c: [u64; D] =
            std::array::from_fn(|k| ((p[k] / length * cells) as u64).min(cells as u64 - 1));
        (0..21).fold(0u64, |acc, bit| {
            (0..D).fold(acc, |acc, k| {
                acc | (((c[k] >> bit) & 1) << (bit * D as u64 + k as u64))
            })
        })
    };
    positions.sort_by_cached_key(key);
}
