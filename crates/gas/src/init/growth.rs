//! Dense initial states by growing the spheres (Lubachevsky & Stillinger, J. Stat. Phys. 60,
//! 561 (1990); Skoge, Donev, Stillinger & Torquato, Phys. Rev. E 74, 041127 (2006)): spheres
//! placed at a low packing fraction in the final box grow at a constant rate while they move
//! and collide event by event, until they have their final size. Every radius is its final
//! radius times s(t) = s0 + g t, so a mixture keeps its size ratios.
//!
//! A pair at separation r (vector from i to j) with relative velocity v touches when
//! |r + v tau| = sigma0 + a tau (sigma0 the contact distance now, a = (r_i + r_j) g its rate
//! of growth): A tau^2 + 2 B tau + C = 0 with A = v.v - a^2, B = r.v - sigma0 a,
//! C = r.r - sigma0^2 >= 0, whose first root is tau = C / (-B + sqrt(B^2 - A C)) (no
//! cancellation) if A < 0 (the growth outruns the relative motion: they always meet) or
//! B < 0 with B^2 >= A C. At contact the normal relative velocity u = v.n is reflected in the
//! frame of the growing contact: u' - a = -(u - a), the impulse that makes the spheres part
//! faster than they grow (energy goes in; the velocities are rescaled to the temperature
//! every 10 collisions per particle). The spheres end a relative 1e-9 larger than their final
//! size and are then set to it: the state has no overlap.

use crate::cells::{CellGrid, NONE};
use crate::error::{Error, Result};
use crate::sorter::{Sorter, SorterKind};
use crate::system::{ball_volume, dot, minimum_image, wrap, Vector};

/// The growth rate of the largest contact distance in thermal speeds sqrt(T / m_min): Skoge
/// et al.'s compression rate gamma. Fast enough to cost a few hundred collisions per
/// particle, slow enough that hard spheres in 3D jam only near random close packing (0.64)
/// and disks near 0.84, above the densities this start reaches.
pub const GROWTH_RATE: f64 = 0.02;

/// Collisions per particle between two rescalings of the velocities to the temperature
/// (each re-predicts every event; the growth heats the gas by a few per cent per collision
/// per particle meanwhile).
const RESCALE_COLLISIONS_PER_PARTICLE: u64 = 10;

/// The most collisions per particle a growth may take before it is declared jammed.
pub const MAX_COLLISIONS_PER_PARTICLE: f64 = 1e5;

/// What a growth did (the cost of a dense start).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrowthReport {
    /// The packing fraction the spheres started from.
    pub start_fraction: f64,
    pub collisions: u64,
    /// Collisions and cell crossings processed.
    pub events: u64,
    /// Rescalings of the velocities to the temperature.
    pub rescalings: u64,
    pub seconds: f64,
}

/// One particle's earliest event.
#[derive(Debug, Clone, Copy)]
struct Next {
    collision: f64,
    partner: u32,
    partner_count: u32,
    crossing: f64,
    exit_dim: u8,
    exit_up: bool,
}

impl Next {
    /// No event predicted.
    const NONE: Next = Next {
        collision: f64::INFINITY,
        partner: NONE,
        partner_count: 0,
        crossing: f64::INFINITY,
        exit_dim: 0,
        exit_up: false,
    };
}

/// The spheres while they grow.
struct Grower<const D: usize> {
    sides: Vector<D>,
    /// Positions at `at`, velocities, final radii, masses, collision counts.
    position: Vec<Vector<D>>,
    velocity: Vec<Vector<D>>,
    at: Vec<f64>,
    radius: Vec<f64>,
    mass: Vec<f64>,
    count: Vec<u32>,
    next: Vec<Next>,
    cells: CellGrid<D>,
    queue: Sorter,
    time: f64,
    /// s(t) = s0 + rate t.
    s0: f64,
    rate: f64,
    temperature: f64,
}

/// Grows spheres of final `radii` and `masses`, placed at `positions` (no overlap at the
/// scale `s0` of their final radii) in the periodic box with `sides`, from scale `s0`
/// to 1, with velocities `velocities` kept at `temperature`; returns their positions (no
/// overlap at the final radii) and the report. Fails if they jam before (more than
/// [`MAX_COLLISIONS_PER_PARTICLE`]) or the box holds fewer than 4 cells of the largest
/// final diameter per side.
pub(crate) fn grow<const D: usize>(
    sides: Vector<D>,
    positions: Vec<Vector<D>>,
    velocities: Vec<Vector<D>>,
    radii: &[f64],
    masses: &[f64],
    s0: f64,
    temperature: f64,
) -> Result<(Vec<Vector<D>>, GrowthReport)> {
    let clock = std::time::Instant::now();
    let n = positions.len();
    let largest = radii.iter().copied().fold(0.0, f64::max);
    let lightest = masses.iter().copied().fold(f64::INFINITY, f64::min);
    let cells = CellGrid::<D>::new(&sides, 2.0 * largest * (1.0 + 1e-6), n);
    if cells.grid.fewest_per_side() < 4 {
        return Err(Error::BoxTooSmall {
            length: sides.iter().copied().fold(f64::INFINITY, f64::min),
            width: 2.0 * largest,
        });
    }
    let rate = GROWTH_RATE * (temperature / lightest).sqrt() / (2.0 * largest);
    let mut g = Grower {
        sides,
        position: positions
            .iter()
            .map(|p| std::array::from_fn(|k| wrap(p[k], sides[k])))
            .collect(),
        velocity: velocities,
        at: vec![0.0; n],
        radius: radii.to_vec(),
        mass: masses.to_vec(),
        count: vec![0; n],
        next: vec![Next::NONE; n],
        cells,
        queue: Sorter::new(SorterKind::Heap, n),
        time: 0.0,
        s0,
        rate,
        temperature,
    };
    for i in 0..n {
        let c = g.cells.coords_of(&g.position[i]);
        g.cells.insert(i, c);
    }
    let end = (1.0 + 1e-9 - s0) / rate;
    let mut report = GrowthReport {
        start_fraction: 0.0,
        collisions: 0,
        events: 0,
        rescalings: 0,
        seconds: 0.0,
    };
    g.rescale();
    let mut since_rescale = 0u64;
    let limit = (MAX_COLLISIONS_PER_PARTICLE * n as f64 / 2.0) as u64;
    while let Some((i, t)) = g.queue.peek() {
        if t > end {
            break;
        }
        g.time = t;
        report.events += 1;
        let next = g.next[i];
        if next.crossing <= next.collision {
            g.bring_to_now(i);
            g.cells.shift(i, next.exit_dim as usize, next.exit_up);
            g.predict_after_crossing(i, next.exit_dim as usize, next.exit_up);
        } else {
            let j = next.partner as usize;
            if g.count[j] == next.partner_count {
                g.collide(i, j);
                report.collisions += 1;
                since_rescale += 1;
                g.predict(i);
                g.predict(j);
            } else {
                g.predict(i);
            }
        }
        if since_rescale >= RESCALE_COLLISIONS_PER_PARTICLE * n as u64 / 2 {
            g.rescale();
            report.rescalings += 1;
            since_rescale = 0;
        }
        if report.collisions > limit {
            let volume: f64 = g.radius.iter().map(|&r| ball_volume::<D>(r)).sum();
            return Err(Error::Jammed {
                phi: volume * g.scale().powi(D as i32) / crate::system::box_volume(&sides),
                collisions_per_particle: MAX_COLLISIONS_PER_PARTICLE,
            });
        }
    }
    g.time = end;
    let positions = (0..n).map(|i| g.now(i)).collect();
    report.seconds = clock.elapsed().as_secs_f64();
    Ok((positions, report))
}

impl<const D: usize> Grower<D> {
    /// The scale s of the radii now.
    fn scale(&self) -> f64 {
        self.s0 + self.rate * self.time
    }

    /// The position of i now, in the box.
    fn now(&self, i: usize) -> Vector<D> {
        let p = self.unwrapped(i);
        std::array::from_fn(|k| wrap(p[k], self.sides[k]))
    }

    /// The position of i now, possibly just outside the box (differences take the minimum
    /// image).
    #[inline]
    fn unwrapped(&self, i: usize) -> Vector<D> {
        let dt = self.time - self.at[i];
        let (p, v) = (&self.position[i], &self.velocity[i]);
        std::array::from_fn(|k| p[k] + v[k] * dt)
    }

    fn bring_to_now(&mut self, i: usize) {
        self.position[i] = self.now(i);
        self.at[i] = self.time;
    }

    /// Every particle to the present, velocities scaled to the temperature (the mean
    /// velocity, conserved, stays), every event predicted afresh.
    fn rescale(&mut self) {
        let n = self.position.len();
        for i in 0..n {
            self.bring_to_now(i);
        }
        let mean = crate::observe::mass_weighted_mean(&self.velocity, &self.mass);
        let kinetic: f64 = self
            .velocity
            .iter()
            .zip(&self.mass)
            .map(|(v, m)| {
                let c: Vector<D> = std::array::from_fn(|k| v[k] - mean[k]);
                m * dot(&c, &c)
            })
            .sum::<f64>()
            / (n * D) as f64;
        let factor = if kinetic > 0.0 {
            (self.temperature / kinetic).sqrt()
        } else {
            1.0
        };
        for v in &mut self.velocity {
            for k in 0..D {
                v[k] = mean[k] + (v[k] - mean[k]) * factor;
            }
        }
        for i in 0..n {
            self.predict(i);
        }
    }

    /// The earliest collision and cell crossing of i, scheduled.
    fn predict(&mut self, i: usize) {
        let (cells, count) = self.cells.grid.neighbor_cells(&self.cells.coords[i]);
        let mut next = self.crossing(i);
        self.scan(i, &cells[..count], &mut next);
        self.schedule(i, next);
    }

    /// After i crossed into a new cell along `dim`: its collision stays (its velocity did
    /// not change), the new crossing and the layer of cells beyond are predicted.
    fn predict_after_crossing(&mut self, i: usize, dim: usize, up: bool) {
        let (cells, count) = self.cells.grid.layer_cells(&self.cells.coords[i], dim, up);
        let old = self.next[i];
        let mut next = self.crossing(i);
        (next.collision, next.partner, next.partner_count) =
            (old.collision, old.partner, old.partner_count);
        self.scan(i, &cells[..count], &mut next);
        self.schedule(i, next);
    }

    fn schedule(&mut self, i: usize, next: Next) {
        self.next[i] = next;
        self.queue.update(i, next.collision.min(next.crossing));
    }

    /// i's next cell crossing, no collision.
    fn crossing(&self, i: usize) -> Next {
        let (p, v) = (self.unwrapped(i), self.velocity[i]);
        let mut next = Next::NONE;
        if let Some((dt, dim, up)) = self.cells.grid.exit(&self.cells.coords[i], &p, &v) {
            next.crossing = self.time + dt;
            next.exit_dim = dim as u8;
            next.exit_up = up;
        }
        next
    }

    /// Keeps in `next` i's earliest collision with the particles of `cells`.
    fn scan(&self, i: usize, cells: &[usize], next: &mut Next) {
        let p = self.unwrapped(i);
        let v = self.velocity[i];
        let s = self.scale();
        for &cell in cells {
            self.cells.for_each_in_cell(cell, |j| {
                if j == i {
                    return;
                }
                let q = self.unwrapped(j);
                let r: Vector<D> =
                    std::array::from_fn(|k| minimum_image(q[k] - p[k], self.sides[k]));
                let w: Vector<D> = std::array::from_fn(|k| self.velocity[j][k] - v[k]);
                let contact = self.radius[i] + self.radius[j];
                let (sigma, a) = (contact * s, contact * self.rate);
                let aa = dot(&w, &w) - a * a;
                let b = dot(&r, &w) - sigma * a;
                let c = dot(&r, &r) - sigma * sigma;
                let tau = if c <= 0.0 {
                    (b < 0.0).then_some(0.0)
                } else {
                    let disc = b * b - aa * c;
                    (aa < 0.0 || (b < 0.0 && disc >= 0.0)).then(|| c / (-b + disc.max(0.0).sqrt()))
                };
                if let Some(tau) = tau {
                    if self.time + tau < next.collision {
                        next.collision = self.time + tau;
                        next.partner = j as u32;
                        next.partner_count = self.count[j];
                    }
                }
            });
        }
    }

    /// The collision of i and j now: the normal relative velocity reflected in the frame of
    /// the growing contact.
    fn collide(&mut self, i: usize, j: usize) {
        self.bring_to_now(i);
        self.bring_to_now(j);
        let r: Vector<D> = std::array::from_fn(|k| {
            minimum_image(self.position[j][k] - self.position[i][k], self.sides[k])
        });
        let distance = dot(&r, &r).sqrt();
        let normal: Vector<D> = std::array::from_fn(|k| r[k] / distance);
        let w: Vector<D> = std::array::from_fn(|k| self.velocity[j][k] - self.velocity[i][k]);
        let u = dot(&w, &normal);
        let a = (self.radius[i] + self.radius[j]) * self.rate;
        let change = 2.0 * (a - u);
        let (mi, mj) = (self.mass[i], self.mass[j]);
        for (k, n) in normal.iter().enumerate() {
            self.velocity[i][k] -= change * mj / (mi + mj) * n;
            self.velocity[j][k] += change * mi / (mi + mj) * n;
        }
        self.count[i] = self.count[i].wrapping_add(1);
        self.count[j] = self.count[j].wrapping_add(1);
    }
}
