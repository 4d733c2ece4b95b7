//! Initial states: non-overlapping random positions at a given packing fraction and
//! Maxwellian velocities at a given temperature with zero total momentum, for one kind of
//! sphere ([`monodisperse`]) or a mixture of several ([`polydisperse`]). Positions: random
//! sequential addition up to [`RANDOM_ADDITION_LIMIT`], a melted lattice up to
//! [`lattice_limit`], above it (to [`packing_limit`]: 0.60 in 3D, 0.80 in 2D) spheres grown
//! from the random addition's density by event-driven MD ([`growth`], Lubachevsky &
//! Stillinger), whose cost the `_reporting` forms return.

mod growth;

pub use growth::{GrowthReport, GROWTH_RATE};

use crate::cells::CellGrid;
use crate::error::{require_positive, Error, Result};
use crate::system::{
    ball_volume, box_side, box_volume, dot, is_cube, monodisperse_box_side, System, Vector,
};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_pcg::Pcg64;

/// Packing fraction up to which positions are placed by random sequential addition; above
/// it on a lattice, melted by elastic collisions ([`melt`]).
pub const RANDOM_ADDITION_LIMIT: f64 = 0.3;

/// The box of an initial state: a cube holding the spheres at a packing fraction, or a box
/// with sides of its own (the packing fraction is then the spheres' volume over the box's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BoxSize<const D: usize> {
    PackingFraction(f64),
    Sides(Vector<D>),
}

impl<const D: usize> From<f64> for BoxSize<D> {
    fn from(phi: f64) -> Self {
        BoxSize::PackingFraction(phi)
    }
}

impl<const D: usize> From<Vector<D>> for BoxSize<D> {
    fn from(sides: Vector<D>) -> Self {
        BoxSize::Sides(sides)
    }
}

impl<const D: usize> BoxSize<D> {
    /// The sides and the packing fraction of spheres of total volume `sphere_volume`;
    /// `cube_side` computes the side of the cube at a packing fraction.
    fn resolve(self, sphere_volume: f64, cube_side: impl Fn(f64) -> f64) -> (Vector<D>, f64) {
        match self {
            BoxSize::PackingFraction(phi) => ([cube_side(phi); D], phi),
            BoxSize::Sides(sides) => (sides, sphere_volume / box_volume(&sides)),
        }
    }

    /// The key that sets the box, for errors.
    fn key(self) -> &'static str {
        match self {
            BoxSize::PackingFraction(_) => "packing_fraction",
            BoxSize::Sides(_) => "box",
        }
    }

    /// Sides finite and > 0.
    fn check(self) -> Result<()> {
        if let BoxSize::Sides(sides) = self {
            for (k, &l) in sides.iter().enumerate() {
                require_positive(&format!("box[{k}]"), l)?;
            }
        }
        Ok(())
    }
}

/// A monodisperse gas: `n` spheres of diameter `diameter` and mass `mass` at packing
/// fraction `phi`, temperature `temperature` (T = m <v^2> / D), all fixed by `seed`.
pub fn monodisperse<const D: usize>(
    n: usize,
    phi: f64,
    diameter: f64,
    mass: f64,
    temperature: f64,
    seed: u64,
) -> Result<System<D>> {
    monodisperse_reporting(n, phi, diameter, mass, temperature, seed, [false; D])
        .map(|(system, _)| system)
}

/// [`monodisperse`] in a box of `size` (a packing fraction, or sides of its own) whose axes
/// `closed` have walls (every centre at least its radius from them; the same random
/// numbers as the periodic start), and the report of the growth of a dense start (above
/// [`lattice_limit`]; not in a container yet).
pub fn monodisperse_reporting<const D: usize>(
    n: usize,
    size: impl Into<BoxSize<D>>,
    diameter: f64,
    mass: f64,
    temperature: f64,
    seed: u64,
    closed: [bool; D],
) -> Result<(System<D>, Option<GrowthReport>)> {
    let size = size.into();
    size.check()?;
    let volume = n as f64 * ball_volume::<D>(0.5 * diameter);
    let (sides, phi) = size.resolve(volume, |phi| monodisperse_box_side::<D>(n, diameter, phi));
    check_count_and_packing::<D>(n, phi, size.key())?;
    let mut rng = Pcg64::seed_from_u64(seed);
    let (positions, grown_report) = if phi > lattice_limit(D) {
        refuse_growth_in_container(phi, &closed)?;
        let (positions, report) =
            grown::<D>(sides, phi, &vec![diameter; n], &vec![mass; n], &mut rng)?;
        (positions, Some(report))
    } else if phi <= RANDOM_ADDITION_LIMIT {
        let positions =
            random_addition::<D>(sides, &vec![diameter; n], diameter, closed, &mut rng)?;
        (positions, None)
    } else {
        (lattice::<D>(n, sides, diameter)?, None)
    };
    let positions = space_order(&positions, sides, diameter)
        .into_iter()
        .map(|i| positions[i])
        .collect();
    let velocities = maxwellian::<D>(n, mass, temperature, &mut rng);
    let system = System {
        sides,
        positions,
        velocities,
        radii: vec![0.5 * diameter; n],
        masses: vec![mass; n],
    };
    // A lattice is melted; random and grown positions are already disordered.
    if phi <= RANDOM_ADDITION_LIMIT || grown_report.is_some() {
        Ok((system, grown_report))
    } else {
        Ok((
            melt_in(system, MELTING_COLLISIONS_PER_PARTICLE, closed)?,
            None,
        ))
    }
}

/// Dense starts are grown in the periodic box only (for now): refused in a container.
fn refuse_growth_in_container(phi: f64, closed: &[bool]) -> Result<()> {
    if closed.iter().any(|&c| c) {
        return Err(Error::out_of_range(
            "packing_fraction",
            phi,
            "up to the lattice limit in a container with walls (dense starts are grown in \
             the periodic box only)",
        ));
    }
    Ok(())
}

/// Positions of spheres of `diameters` at packing fraction `phi` in the box with `sides`,
/// grown ([`growth`]) from random sequential addition at [`RANDOM_ADDITION_LIMIT`]
/// (scaled down by s0 = (0.3 / phi)^(1/D)), with velocities from `rng` at unit temperature.
fn grown<const D: usize>(
    sides: Vector<D>,
    phi: f64,
    diameters: &[f64],
    masses: &[f64],
    rng: &mut Pcg64,
) -> Result<(Vec<Vector<D>>, GrowthReport)> {
    let s0 = (RANDOM_ADDITION_LIMIT / phi).powf(1.0 / D as f64);
    let small: Vec<f64> = diameters.iter().map(|d| d * s0).collect();
    let largest = small.iter().copied().fold(0.0, f64::max);
    let positions = random_addition::<D>(sides, &small, largest, [false; D], rng)?;
    let velocities: Vec<Vector<D>> = masses
        .iter()
        .map(|&m| std::array::from_fn(|_| rng.sample::<f64, _>(StandardNormal) / m.sqrt()))
        .collect();
    let radii: Vec<f64> = diameters.iter().map(|d| 0.5 * d).collect();
    let (positions, mut report) =
        growth::grow::<D>(sides, positions, velocities, &radii, masses, s0, 1.0)?;
    report.start_fraction = RANDOM_ADDITION_LIMIT;
    Ok((positions, report))
}

/// One kind of sphere in a mixture: diameter, mass and number fraction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Species {
    pub diameter: f64,
    pub mass: f64,
    /// Fraction of the particles (normalized over all species).
    pub fraction: f64,
}

/// Particles of each species among `n`: the normalized fractions times `n`, rounded down,
/// and the particles left over given to the largest remainders (the earlier species on a
/// tie), so that the counts sum to `n`. Fails for a bad fraction or a species without a
/// particle.
pub fn species_counts(n: usize, species: &[Species]) -> Result<Vec<usize>> {
    if species.is_empty() {
        return Err(Error::out_of_range(
            "species",
            "an empty list",
            "at least one species",
        ));
    }
    for (s, x) in species.iter().enumerate() {
        if !(x.fraction.is_finite() && x.fraction > 0.0) {
            return Err(Error::out_of_range(
                format!("species[{s}].fraction"),
                x.fraction,
                "a finite number > 0",
            ));
        }
    }
    let total: f64 = species.iter().map(|x| x.fraction).sum();
    if !total.is_finite() {
        return Err(Error::out_of_range(
            "species",
            "fractions that sum to infinity",
            "finite fractions",
        ));
    }
    let exact: Vec<f64> = species
        .iter()
        .map(|x| x.fraction / total * n as f64)
        .collect();
    let mut counts: Vec<usize> = exact.iter().map(|x| x.floor() as usize).collect();
    let assigned: usize = counts.iter().sum();
    let mut by_remainder: Vec<usize> = (0..species.len()).collect();
    by_remainder.sort_by(|&a, &b| {
        let (ra, rb) = (exact[a] - exact[a].floor(), exact[b] - exact[b].floor());
        rb.total_cmp(&ra).then(a.cmp(&b))
    });
    for &s in by_remainder.iter().cycle().take(n.saturating_sub(assigned)) {
        counts[s] += 1;
    }
    // Round-off could (in principle) push a floor over an integer: keep the sum at n.
    for _ in n..assigned {
        let largest = (0..counts.len()).max_by_key(|&s| counts[s]).unwrap_or(0);
        counts[largest] -= 1;
    }
    if let Some(s) = counts.iter().position(|&c| c == 0) {
        return Err(Error::out_of_range(
            format!("species[{s}].fraction"),
            species[s].fraction,
            format!(
                "a fraction that gives at least one particle of {n} (fractions are normalized)"
            ),
        ));
    }
    Ok(counts)
}

/// A mixture: `n` spheres of the given species (counts from [`species_counts`]) at packing
/// fraction `phi` (the volume of all spheres over the box volume) and temperature
/// `temperature`, all fixed by `seed`.
///
/// Velocities are Gaussian with variance T / m_i per component, so that every species has
/// the temperature T = m <v^2> / D in expectation; the total momentum is then removed and
/// all velocities rescaled so that the temperature of the whole system, sum m v^2 / (N D),
/// is `temperature` (both up to round-off). Up to [`RANDOM_ADDITION_LIMIT`] the spheres are
/// placed by random sequential addition (largest first, contact distance
/// (d_i + d_j) / 2); above it on a simple lattice with spacing at least the largest
/// diameter (species on random sites), melted by elastic collisions ([`melt`]), or, where
/// that lattice does not fit or above [`lattice_limit`], grown ([`growth`]). Particles
/// are ordered in space, so the species are mixed in memory.
pub fn polydisperse<const D: usize>(
    n: usize,
    phi: f64,
    species: &[Species],
    temperature: f64,
    seed: u64,
) -> Result<System<D>> {
    polydisperse_reporting(n, phi, species, temperature, seed, [false; D]).map(|(system, _)| system)
}

/// [`polydisperse`] in a box whose axes `closed` have walls (as
/// [`monodisperse_reporting`]), and the report of the growth of a dense start.
pub fn polydisperse_reporting<const D: usize>(
    n: usize,
    size: impl Into<BoxSize<D>>,
    species: &[Species],
    temperature: f64,
    seed: u64,
    closed: [bool; D],
) -> Result<(System<D>, Option<GrowthReport>)> {
    let size = size.into();
    size.check()?;
    if let BoxSize::PackingFraction(phi) = size {
        check_count_and_packing::<D>(n, phi, size.key())?;
    }
    require_positive("temperature", temperature)?;
    for (s, x) in species.iter().enumerate() {
        for (name, value) in [("diameter", x.diameter), ("mass", x.mass)] {
            require_positive(&format!("species[{s}].{name}"), value)?;
        }
    }
    let counts = species_counts(n, species)?;
    // Blocks of species, largest diameter first (random addition places big spheres best
    // into an empty box).
    let mut by_size: Vec<usize> = (0..species.len()).collect();
    by_size.sort_by(|&a, &b| species[b].diameter.total_cmp(&species[a].diameter));
    let mut kind: Vec<usize> = Vec::with_capacity(n);
    for &s in &by_size {
        kind.resize(kind.len() + counts[s], s);
    }
    let max_diameter = species[by_size[0]].diameter;
    let volume: f64 = kind
        .iter()
        .map(|&s| ball_volume::<D>(0.5 * species[s].diameter))
        .sum();
    let (sides, phi) = size.resolve(volume, |phi| box_side::<D>(volume, phi));
    check_count_and_packing::<D>(n, phi, size.key())?;
    let mut rng = Pcg64::seed_from_u64(seed);
    let dense = phi > RANDOM_ADDITION_LIMIT;
    let mut report = None;
    let lattice_fits = lattice_spacing(n, &sides) >= max_diameter;
    let positions = if phi > lattice_limit(D) || (dense && !lattice_fits) {
        refuse_growth_in_container(phi, &closed)?;
        kind.shuffle(&mut rng);
        let diameters: Vec<f64> = kind.iter().map(|&s| species[s].diameter).collect();
        let masses: Vec<f64> = kind.iter().map(|&s| species[s].mass).collect();
        let (positions, grew) = grown::<D>(sides, phi, &diameters, &masses, &mut rng)?;
        report = Some(grew);
        positions
    } else if dense {
        kind.shuffle(&mut rng);
        lattice::<D>(n, sides, max_diameter)?
    } else {
        let diameters: Vec<f64> = kind.iter().map(|&s| species[s].diameter).collect();
        random_addition::<D>(sides, &diameters, max_diameter, closed, &mut rng)?
    };
    let order = space_order(&positions, sides, max_diameter);
    let positions: Vec<Vector<D>> = order.iter().map(|&i| positions[i]).collect();
    let kind: Vec<usize> = order.iter().map(|&i| kind[i]).collect();
    let masses: Vec<f64> = kind.iter().map(|&s| species[s].mass).collect();
    let mut velocities: Vec<Vector<D>> = masses
        .iter()
        .map(|&m| {
            let width = (temperature / m).sqrt();
            std::array::from_fn(|_| width * rng.sample::<f64, _>(StandardNormal))
        })
        .collect();
    set_momentum_and_temperature(&mut velocities, &masses, temperature);
    let system = System {
        sides,
        positions,
        velocities,
        radii: kind.iter().map(|&s| 0.5 * species[s].diameter).collect(),
        masses,
    };
    if !dense || report.is_some() {
        return Ok((system, report));
    }
    let mut system = melt_in(system, MELTING_COLLISIONS_PER_PARTICLE, closed)?;
    // Melting conserves both up to round-off; restore them exactly.
    set_momentum_and_temperature(&mut system.velocities, &system.masses, temperature);
    Ok((system, None))
}

/// Removes the total momentum, then rescales the velocities so that
/// sum m v^2 / (N D) = temperature.
fn set_momentum_and_temperature<const D: usize>(
    velocities: &mut [Vector<D>],
    masses: &[f64],
    temperature: f64,
) {
    let mean = crate::observe::mass_weighted_mean(velocities, masses);
    for v in velocities.iter_mut() {
        for k in 0..D {
            v[k] -= mean[k];
        }
    }
    let current = velocities
        .iter()
        .zip(masses)
        .map(|(v, m)| m * dot(v, v))
        .sum::<f64>()
        / (velocities.len() * D) as f64;
    let scale = (temperature / current).sqrt();
    for v in velocities.iter_mut() {
        for c in v.iter_mut() {
            *c *= scale;
        }
    }
}

/// Elastic collisions per particle that melt the lattice of a dense initial state.
pub const MELTING_COLLISIONS_PER_PARTICLE: u64 = 10;

/// Runs elastic event-driven MD for `per_particle` collisions per particle (energy and
/// momentum are conserved exactly up to round-off, so T stays the initial temperature)
/// and returns the state: the lattice order is gone, the velocities are Maxwellian.
pub fn melt<const D: usize>(system: System<D>, per_particle: u64) -> Result<System<D>> {
    melt_in(system, per_particle, [false; D])
}

/// [`melt`] between elastic walls on the axes `closed`.
fn melt_in<const D: usize>(
    system: System<D>,
    per_particle: u64,
    closed: [bool; D],
) -> Result<System<D>> {
    use crate::walls::{Side, Wall, WallKind, Walls};
    use crate::Engine;
    let n = system.len() as u64;
    let elastic = restitution::Constant::new(1.0)?;
    let mut engine = crate::EventDriven::new(system, Box::new(elastic))?;
    if closed.iter().any(|&c| c) {
        let walls = (0..D)
            .filter(|&k| closed[k])
            .flat_map(|axis| {
                [Side::Low, Side::High].map(|side| Wall {
                    axis,
                    side,
                    kind: WallKind::Elastic,
                })
            })
            .collect();
        engine.set_walls(Some(Walls::new(walls, 0)?))?;
    }
    engine.run_collisions(per_particle * n / 2);
    Ok(engine.system().clone())
}

/// At least two particles, and a packing fraction the initializer accepts (set by `key`:
/// the packing fraction, or the box).
fn check_count_and_packing<const D: usize>(n: usize, phi: f64, key: &str) -> Result<()> {
    if n < 2 {
        return Err(Error::out_of_range("particles", n, "at least 2"));
    }
    if !(phi > 0.0 && phi <= max_packing::<D>()) {
        let value = if key == "packing_fraction" {
            phi.to_string()
        } else {
            format!("a box the spheres fill to phi = {phi}")
        };
        return Err(Error::out_of_range(
            key,
            value,
            format!("0 < phi <= {}", max_packing::<D>()),
        ));
    }
    Ok(())
}

/// Packing fractions the initializer accepts in D dimensions.
pub fn max_packing<const D: usize>() -> f64 {
    packing_limit(D)
}

/// Packing fractions the initializer accepts in `dimension` dimensions (1, 2, 3): 0.9,
/// 0.8, 0.6 — below random close packing (0.64 in 3D, 0.84 for disks), which growing
/// spheres reach only by jamming.
pub fn packing_limit(dimension: usize) -> f64 {
    match dimension {
        1 => 0.9,
        2 => 0.8,
        _ => 0.6,
    }
}

/// The packing fraction up to which a dense start is a melted simple lattice (0.9, 0.7,
/// 0.45 in 1, 2, 3 dimensions: the lattice then melts within
/// [`MELTING_COLLISIONS_PER_PARTICLE`]); above it the spheres are grown.
pub fn lattice_limit(dimension: usize) -> f64 {
    match dimension {
        1 => 0.9,
        2 => 0.7,
        _ => 0.45,
    }
}

/// The error of a simple lattice of spacing `spacing` that cannot hold spheres of
/// `diameter`, with the highest packing fraction that would fit.
fn lattice_too_dense<const D: usize>(phi: f64, diameter: f64, spacing: f64) -> Error {
    Error::LatticeTooDense {
        phi,
        diameter,
        spacing,
        max_phi: RANDOM_ADDITION_LIMIT
            .max((phi * (spacing / diameter).powi(D as i32) * 1e4).floor() / 1e4),
    }
}

/// Places spheres of the given diameters one after the other at random positions where
/// they overlap no sphere placed before (cells at least `max_diameter` wide); on the axes
/// `closed` (walls) within their radius of neither face, with no periodic image.
fn random_addition<const D: usize>(
    sides: Vector<D>,
    diameters: &[f64],
    max_diameter: f64,
    closed: [bool; D],
    rng: &mut Pcg64,
) -> Result<Vec<Vector<D>>> {
    let n = diameters.len();
    let mut grid = CellGrid::<D>::new(&sides, max_diameter, n);
    let mut positions: Vec<Vector<D>> = Vec::with_capacity(n);
    let system = System::<D> {
        sides,
        positions: vec![],
        velocities: vec![],
        radii: vec![],
        masses: vec![],
    };
    for (i, &di) in diameters.iter().enumerate() {
        let mut placed = false;
        for _ in 0..100_000 {
            let p: Vector<D> = std::array::from_fn(|k| {
                let u = rng.random::<f64>();
                if closed[k] {
                    0.5 * di + u * (sides[k] - di)
                } else {
                    u * sides[k]
                }
            });
            let c = grid.coords_of(&p);
            let mut free = true;
            grid.for_each_neighbor(&c, |j| {
                let mut d = system.separation(&p, &positions[j]);
                for k in (0..D).filter(|&k| closed[k]) {
                    d[k] = positions[j][k] - p[k];
                }
                let sigma = contact(di, diameters[j]);
                free &= dot(&d, &d) >= sigma * sigma;
            });
            if free {
                positions.push(p);
                grid.insert(i, c);
                placed = true;
                break;
            }
        }
        if !placed {
            return Err(Error::Placement { particle: i });
        }
    }
    Ok(positions)
}

/// Contact distance (d_i + d_j) / 2 (exactly d for equal diameters).
#[inline]
fn contact(di: f64, dj: f64) -> f64 {
    if di == dj {
        di
    } else {
        0.5 * (di + dj)
    }
}

/// Sites of a simple lattice for `n` spheres in a box with `sides`: ceil(n^(1/D)) per side
/// in a cube; in another box a number per axis in proportion to its side (as near to
/// equal spacings as whole numbers allow), at least n sites in all.
fn lattice_sites<const D: usize>(n: usize, sides: &Vector<D>) -> [usize; D] {
    if is_cube(sides) {
        return [(n as f64).powf(1.0 / D as f64).ceil() as usize; D];
    }
    let density = (n as f64 / box_volume(sides)).powf(1.0 / D as f64);
    let mut sites: [usize; D] =
        std::array::from_fn(|k| ((sides[k] * density).floor() as usize).max(1));
    // Add a row along the axis of the widest spacing until the sites hold n.
    while sites.iter().product::<usize>() < n {
        let k = (0..D)
            .max_by(|&a, &b| (sides[a] / sites[a] as f64).total_cmp(&(sides[b] / sites[b] as f64)))
            .unwrap_or(0);
        sites[k] += 1;
    }
    sites
}

/// The smallest spacing of [`lattice_sites`].
fn lattice_spacing<const D: usize>(n: usize, sides: &Vector<D>) -> f64 {
    let sites = lattice_sites(n, sides);
    (0..D)
        .map(|k| sides[k] / sites[k] as f64)
        .fold(f64::INFINITY, f64::min)
}

fn lattice<const D: usize>(n: usize, sides: Vector<D>, diameter: f64) -> Result<Vec<Vector<D>>> {
    let sites = lattice_sites(n, &sides);
    let spacing: [f64; D] = std::array::from_fn(|k| sides[k] / sites[k] as f64);
    let smallest = spacing.iter().copied().fold(f64::INFINITY, f64::min);
    if smallest < diameter {
        let phi = n as f64 * ball_volume::<D>(0.5 * diameter) / box_volume(&sides);
        return Err(lattice_too_dense::<D>(phi, diameter, smallest));
    }
    Ok((0..n)
        .map(|i| {
            let mut rest = i;
            std::array::from_fn(|k| {
                let x = rest % sites[k];
                rest /= sites[k];
                (x as f64 + 0.5) * spacing[k]
            })
        })
        .collect())
}

/// Velocities of particles of `masses` from the Maxwellian at `temperature`, for particles
/// placed by someone else (a file): each component Gaussian of variance T/m_i (its own
/// stream of `seed`), the total momentum removed (the mass-weighted mean subtracted), then
/// all scaled by one factor so that sum m_i v_i^2 / (N D) = temperature exactly, as the
/// placements of this module do for one mass ([`maxwellian`]).
pub fn thermal_velocities<const D: usize>(
    masses: &[f64],
    temperature: f64,
    seed: u64,
) -> Vec<Vector<D>> {
    let mut stream = crate::rng::Stream::new(seed, crate::rng::Purpose::Velocities, 0, 0);
    let mut v: Vec<Vector<D>> = masses
        .iter()
        .map(|&m| {
            let scale = (temperature / m).sqrt();
            std::array::from_fn(|_| scale * stream.normal())
        })
        .collect();
    let total: f64 = masses.iter().sum();
    let mean: Vector<D> =
        std::array::from_fn(|k| v.iter().zip(masses).map(|(x, &m)| m * x[k]).sum::<f64>() / total);
    for x in &mut v {
        for k in 0..D {
            x[k] -= mean[k];
        }
    }
    let energy: f64 = v.iter().zip(masses).map(|(x, &m)| m * dot(x, x)).sum();
    let scale = (temperature * (masses.len() * D) as f64 / energy).sqrt();
    for x in &mut v {
        for c in x.iter_mut() {
            *c *= scale;
        }
    }
    v
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

/// The order of `positions` along a Morton (Z-order) curve of cells `width` wide, so that
/// neighbours in space are neighbours in memory (fewer cache misses in large systems).
/// Stable: particles in the same cell keep their order.
fn space_order<const D: usize>(
    positions: &[Vector<D>],
    sides: Vector<D>,
    width: f64,
) -> Vec<usize> {
    let cells: [f64; D] = std::array::from_fn(|k| (sides[k] / width).floor().max(1.0));
    let key = |p: &Vector<D>| -> u64 {
        let c: [u64; D] =
            std::array::from_fn(|k| ((p[k] / sides[k] * cells[k]) as u64).min(cells[k] as u64 - 1));
        (0..21).fold(0u64, |acc, bit| {
            (0..D).fold(acc, |acc, k| {
                acc | (((c[k] >> bit) & 1) << (bit * D as u64 + k as u64))
            })
        })
    };
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by_cached_key(|&i| key(&positions[i]));
    order
}
