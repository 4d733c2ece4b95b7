//! The gases of the shear study: eMD and spatial DSMC in boxes measured in critical
//! lengths, their theory (`gas::theory::HcsTransport`), and their runs through the driver.

use gas::dsmc::{point_gas, SpatialOptions};
use gas::observe::temperature;
use gas::structure::hydrodynamic_modes;
use gas::theory::{long_wavelength_structure_factor, HcsTransport};
use restitution::Constant;
use sim::engines::{self, EngineSpec, Setup};
use sim::error::Result;
use sim::schedule::{Measure, Schedule};

pub(super) fn engine_error(e: impl std::fmt::Display) -> sim::error::Error {
    crate::numerical("engine", e)
}

/// How a case is simulated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Method {
    EventDriven,
    /// Spatial DSMC with this many physical particles per simulated one.
    Dsmc {
        weight: f64,
    },
}

/// One gas in one box.
#[derive(Debug, Clone, Copy)]
pub(super) struct Case {
    pub(super) label: &'static str,
    pub(super) dimension: usize,
    pub(super) phi: f64,
    pub(super) eps: f64,
    pub(super) method: Method,
    /// Box side in critical lengths.
    pub(super) boxes: f64,
    /// Shells 1 <= |n|^2 <= max_norm2.
    pub(super) max_norm2: usize,
    pub(super) collisions: f64,
    pub(super) seeds: u64,
}

impl Case {
    pub(super) fn density(&self) -> f64 {
        match self.dimension {
            2 => self.phi / gas::system::ball_volume::<2>(0.5),
            _ => self.phi / gas::system::ball_volume::<3>(0.5),
        }
    }

    pub(super) fn theory(&self) -> HcsTransport {
        let n = self.density();
        match (self.dimension, self.method) {
            (2, Method::EventDriven) => {
                HcsTransport::new::<2>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
            (2, Method::Dsmc { .. }) => {
                HcsTransport::enskog_factor_dsmc::<2>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
            (_, Method::EventDriven) => {
                HcsTransport::new::<3>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
            (_, Method::Dsmc { .. }) => {
                HcsTransport::enskog_factor_dsmc::<3>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
        }
    }

    /// The mean free path (`gas::theory::mean_free_path`, with the Enskog factor).
    pub(super) fn mean_free_path(&self) -> f64 {
        let n = self.density();
        match self.dimension {
            2 => gas::theory::mean_free_path::<2>(n, 1.0, self.phi),
            _ => gas::theory::mean_free_path::<3>(n, 1.0, self.phi),
        }
    }

    pub(super) fn side(&self) -> f64 {
        self.boxes * self.theory().critical_length()
    }

    /// Physical particles in the box.
    pub(super) fn physical_particles(&self) -> f64 {
        self.density() * self.side().powi(self.dimension as i32)
    }

    /// Simulated particles.
    pub(super) fn particles(&self) -> usize {
        let weight = match self.method {
            Method::EventDriven => 1.0,
            Method::Dsmc { weight } => weight,
        };
        (self.physical_particles() / weight).round() as usize
    }

    pub(super) fn method_name(&self) -> String {
        match self.method {
            Method::EventDriven => "eMD".into(),
            Method::Dsmc { weight } => format!("spatial DSMC, F = {weight}"),
        }
    }
}

/// One run: per sample c, T, t and the transverse energy of each shell.
pub(super) struct Run {
    pub(super) collisions: Vec<f64>,
    pub(super) times: Vec<f64>,
    pub(super) temperatures: Vec<f64>,
    /// `energies[shell][sample]`.
    pub(super) energies: Vec<Vec<f64>>,
    /// |k| of each shell.
    pub(super) wave_numbers: Vec<f64>,
    pub(super) particles: usize,
}

pub(super) fn simulate(case: &Case, seed: u64) -> Result<Run> {
    match case.dimension {
        2 => simulate_in::<2>(case, seed),
        _ => simulate_in::<3>(case, seed),
    }
}

pub(super) fn simulate_in<const D: usize>(case: &Case, seed: u64) -> Result<Run> {
    let law = Box::new(Constant::new(case.eps).map_err(engine_error)?);
    let n = case.particles();
    let side = case.side();
    let setup = Setup {
        law,
        packing_fraction: case.phi,
        seed,
        baths: None,
    };
    let (spec, system) = match case.method {
        // The side of N spheres at phi is the case's side to the rounding of N.
        Method::EventDriven => (
            EngineSpec::EventDriven,
            gas::init::monodisperse::<D>(n, case.phi, 1.0, 1.0, 1.0, seed),
        ),
        Method::Dsmc { .. } => (
            EngineSpec::SpatialDsmc(SpatialOptions::default()),
            point_gas::<D>(n, [side; D], 1.0, 1.0, 1.0, seed),
        ),
    };
    let engine = engines::build(&spec, system.map_err(engine_error)?, setup)?;
    // Points placed independently: S(0) = 1.
    let s0 = match case.method {
        Method::EventDriven => long_wavelength_structure_factor::<D>(case.phi),
        Method::Dsmc { .. } => 1.0,
    };
    // A sample at every collision per particle, 0 ..= the case's collisions.
    let samples = case.collisions.round() as u64;
    let targets: Vec<f64> = (0..=samples).map(|i| i as f64).collect();
    let schedule = Schedule::samples_at(&targets, Measure::CollisionsPerParticle);
    let max_norm2 = case.max_norm2;
    let rows = sim::probe::sample(engine, schedule, move |e| {
        let (c, t) = (e.collisions_per_particle(), e.time());
        let system = e.system();
        let shells: Vec<(f64, f64)> = hydrodynamic_modes(system, max_norm2, s0)
            .iter()
            .map(|s| (s.k, s.transverse_energy))
            .collect();
        (c, t, temperature(system), shells)
    })?;
    let mut run = Run {
        collisions: Vec::new(),
        times: Vec::new(),
        temperatures: Vec::new(),
        energies: Vec::new(),
        wave_numbers: Vec::new(),
        particles: n,
    };
    for (c, t, temperature, shells) in rows {
        if run.energies.is_empty() {
            run.energies = vec![Vec::new(); shells.len()];
            run.wave_numbers = shells.iter().map(|s| s.0).collect();
        }
        for (e, s) in run.energies.iter_mut().zip(&shells) {
            e.push(s.1);
        }
        run.temperatures.push(temperature);
        run.collisions.push(c);
        run.times.push(t);
    }
    Ok(run)
}

pub(super) fn cases(quick: bool) -> Vec<Case> {
    let emd2 = Case {
        label: "2D, phi = 0.05, eps = 0.9",
        dimension: 2,
        phi: 0.05,
        eps: 0.9,
        method: Method::EventDriven,
        boxes: 4.0,
        max_norm2: 10,
        collisions: 120.0,
        seeds: 8,
    };
    if quick {
        // Shells up to |n|^2 = 20 (k up to 1.1 k_c): 12 rows, the stable ones unresolved.
        return vec![Case {
            max_norm2: 20,
            collisions: 70.0,
            seeds: 3,
            ..emd2
        }];
    }
    vec![
        emd2,
        Case {
            label: "2D, phi = 0.25, eps = 0.9",
            phi: 0.25,
            boxes: 6.0,
            max_norm2: 20,
            collisions: 60.0,
            ..emd2
        },
        Case {
            label: "2D, phi = 0.05, eps = 0.8",
            eps: 0.8,
            collisions: 40.0,
            ..emd2
        },
        Case {
            label: "3D, phi = 0.2, eps = 0.9",
            dimension: 3,
            phi: 0.2,
            boxes: 3.0,
            max_norm2: 5,
            collisions: 100.0,
            seeds: 6,
            ..emd2
        },
        Case {
            label: "2D, phi = 0.05, eps = 0.9",
            method: Method::Dsmc { weight: 0.1 },
            collisions: 80.0,
            seeds: 4,
            ..emd2
        },
    ]
}

/// The box below L_c whose modes must stay at their stationary value.
pub(super) fn stable_case(quick: bool) -> Case {
    Case {
        label: "2D, phi = 0.05, eps = 0.9, box L_c / 2",
        dimension: 2,
        phi: 0.05,
        eps: 0.9,
        method: Method::EventDriven,
        boxes: 0.5,
        max_norm2: 1,
        collisions: 120.0,
        seeds: if quick { 8 } else { 32 },
    }
}
