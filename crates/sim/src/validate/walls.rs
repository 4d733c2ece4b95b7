//! `[[wall]]`: the walls of a container. Each names an axis of the box and a side; an axis
//! is closed when both its sides have a wall and periodic when neither has. Each kind takes
//! its own keys only.

use super::LawSpec;
use super::Species;
use crate::description::{
    EngineKind, LawKind, RunDescription, WallKindName, WallSection, WallSide, Waveform, AXIS_NAMES,
};
use crate::engines::{engine_named, kinds_that, Abilities};
use crate::error::{Error, Result};
use gas::walls::Side;
use restitution::{Criterion, FormName};

/// A checked wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallSpec {
    pub axis: usize,
    pub side: Side,
    pub kind: WallSpecKind,
}

/// What a checked wall does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WallSpecKind {
    Elastic,
    /// A wall bouncing spheres with a law of restitution.
    Restitution(WallLaw),
    /// Maxwell's diffuse wall at this temperature.
    Thermal(f64),
    /// A wall moving along its axis, bouncing with a law of restitution in its frame.
    Vibrating {
        law: WallLaw,
        motion: gas::walls::Motion,
    },
}

/// The law of a restitution or vibrating wall (`law`, with the keys of `[collision]`'s law
/// of that name).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WallLaw {
    Constant(f64),
    Dashpot {
        damping_ratio: f64,
        criterion: Criterion,
    },
    Viscoelastic {
        beta: f64,
        form: FormName,
    },
}

impl WallLaw {
    fn spec(&self) -> LawSpec {
        match *self {
            WallLaw::Constant(eps) => LawSpec::Constant(eps),
            WallLaw::Dashpot {
                damping_ratio,
                criterion,
            } => LawSpec::Dashpot {
                damping_ratio,
                criterion,
            },
            WallLaw::Viscoelastic { beta, form } => LawSpec::Viscoelastic { beta, form },
        }
    }
}

impl WallSpecKind {
    /// Whether the wall can give the gas energy.
    pub fn can_heat(&self) -> bool {
        matches!(
            self,
            WallSpecKind::Thermal(_) | WallSpecKind::Vibrating { .. }
        )
    }
}

impl WallSpec {
    /// The wall as the engines take it, wall number `index`, its law for impacts up to
    /// `max_speed` relative to it (errors name the wall's keys).
    pub fn build(&self, index: usize, max_speed: f64) -> Result<gas::walls::Wall> {
        use gas::walls::WallKind;
        let law = |law: &WallLaw| crate::law::wall_law(&law.spec(), max_speed, index);
        let kind = match &self.kind {
            WallSpecKind::Elastic => WallKind::Elastic,
            WallSpecKind::Restitution(l) => WallKind::Restitution(law(l)?),
            WallSpecKind::Thermal(temperature) => WallKind::Thermal {
                temperature: *temperature,
            },
            WallSpecKind::Vibrating { law: l, motion } => WallKind::Vibrating {
                law: law(l)?,
                motion: *motion,
            },
        };
        Ok(gas::walls::Wall {
            axis: self.axis,
            side: self.side,
            kind,
        })
    }
}

/// An upper bound of the impact speeds on the walls of `plan`: the collisions' bound
/// ([`super::Plan::max_impact_speed`]) raised for the hottest thermal wall, plus twice the
/// fastest wall's top speed and the speed of a fall through the box.
pub fn wall_impact_speed(plan: &super::Plan) -> f64 {
    let t0 = plan.description.system.temperature;
    let hottest = plan
        .walls
        .iter()
        .filter_map(|w| match w.kind {
            WallSpecKind::Thermal(t) => Some(t),
            _ => None,
        })
        .fold(t0, f64::max);
    let wall_speed = plan
        .walls
        .iter()
        .filter_map(|w| match w.kind {
            WallSpecKind::Vibrating { motion, .. } => Some(motion.max_speed()),
            _ => None,
        })
        .fold(0.0, f64::max);
    let fall = plan.gravity.as_ref().map_or(0.0, |g| {
        let largest = g.acceleration.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let tallest = plan.description.box_sides().into_iter().fold(0.0, f64::max);
        (2.0 * largest * tallest).sqrt()
    });
    plan.max_impact_speed() * (hottest / t0).sqrt() + 2.0 * wall_speed + fall
}

/// The walls of the run, checked against the dimension and the engine.
pub(crate) fn walls_spec(
    description: &RunDescription,
    engine: &Abilities,
    species: &[Species],
) -> Result<Vec<WallSpec>> {
    let walls = &description.walls;
    if walls.is_empty() {
        return Ok(Vec::new());
    }
    if !engine.walls {
        return Err(Error::input(
            "wall",
            format!(
                "{} has no walls (homogeneous DSMC has no positions); walls run in \
                 run.engine = {}",
                engine_named(description),
                kinds_that(|a| a.walls)
            ),
        ));
    }
    let dimension = description.system.dimension as usize;
    let mut specs: Vec<WallSpec> = Vec::with_capacity(walls.len());
    for (i, wall) in walls.iter().enumerate() {
        let key = |name: &str| format!("wall[{i}].{name}");
        let axis = wall.axis.index();
        if axis >= dimension {
            let allowed = AXIS_NAMES[..dimension].join(", ");
            return Err(Error::out_of_range(
                &key("axis"),
                format!("{} in {dimension} dimensions", wall.axis.name()),
                &allowed,
            ));
        }
        let side = match wall.side {
            WallSide::Low => Side::Low,
            WallSide::High => Side::High,
        };
        if specs.iter().any(|s| s.axis == axis && s.side == side) {
            return Err(Error::input(
                key("side"),
                format!(
                    "a second wall on the {} side of axis {}; allowed: one wall per side",
                    side.name(),
                    wall.axis.name()
                ),
            ));
        }
        let kind = wall_kind(wall, description, species, &key)?;
        if description.run.engine == EngineKind::SoftSphere {
            soft_wall(wall, &key)?;
        }
        specs.push(WallSpec { axis, side, kind });
    }
    check_sweeps(description, &specs, species)?;
    for (i, wall) in walls.iter().enumerate() {
        let sides = specs.iter().filter(|s| s.axis == wall.axis.index()).count();
        if sides != 2 {
            return Err(Error::input(
                format!("wall[{i}].side"),
                format!(
                    "only the {} side of axis {} has a wall; allowed: walls on both sides of \
                     an axis (or none: periodic)",
                    specs[i].side.name(),
                    wall.axis.name()
                ),
            ));
        }
    }
    Ok(specs)
}

/// Soft-sphere walls are contacts of the particles' material: no thermal walls, and no
/// restitution of their own.
fn soft_wall(wall: &WallSection, key: &dyn Fn(&str) -> String) -> Result<()> {
    if wall.kind == WallKindName::Thermal {
        return Err(Error::input(
            key("kind"),
            "run.engine = \"soft-sphere\" has no thermal walls (a soft contact has no \
             temperature); allowed: \"elastic\" (undamped Hertz), \"restitution\" (the \
             material's viscoelastic contact), \"vibrating\"",
        ));
    }
    if let Some((name, _)) = law_keys(wall).into_iter().find(|(_, present)| *present) {
        return Err(Error::input(
            key(name),
            "run.engine = \"soft-sphere\": a wall is a contact of the particles' material \
             ([collision]); leave the wall's law out",
        ));
    }
    if wall.restitution.is_some() {
        return Err(Error::input(
            key("restitution"),
            "run.engine = \"soft-sphere\": a wall is a contact of the particles' material \
             ([collision]), whose restitution follows from it; leave restitution out",
        ));
    }
    Ok(())
}

/// Refuses vibrating walls whose sweeps (2 A each) leave less than the largest diameter
/// of their axis, naming the first one's amplitude.
fn check_sweeps(
    description: &RunDescription,
    specs: &[WallSpec],
    species: &[Species],
) -> Result<()> {
    let sides = description.box_sides();
    let largest = species.iter().map(|s| s.diameter).fold(0.0, f64::max);
    for (axis, &length) in sides.iter().enumerate() {
        let sweeps: Vec<(usize, f64)> = specs
            .iter()
            .enumerate()
            .filter(|(_, s)| s.axis == axis)
            .filter_map(|(i, s)| match s.kind {
                WallSpecKind::Vibrating { motion, .. } => Some((i, 2.0 * motion.amplitude)),
                _ => None,
            })
            .collect();
        let swept: f64 = sweeps.iter().map(|s| s.1).sum();
        if let Some(&(i, _)) = sweeps.first() {
            if swept + largest >= length {
                return Err(Error::out_of_range(
                    &format!("wall[{i}].amplitude"),
                    crate::output::number(swept / 2.0),
                    &format!(
                        "sweeps 2 A of the vibrating walls of an axis below the box side minus \
                         the largest diameter, {}",
                        crate::output::number(length - largest)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// How far a thermal wall's temperature may lie from the gas's initial one, either way:
/// speeds 1e6 times apart. Beyond, the fast particles' events come closer together than
/// the run's clock resolves (a run at t ~ 1 resolves ~1e-16), and the run stalls.
const WALL_TEMPERATURE_RATIO: f64 = 1e12;

/// A wall's kind with its own keys, refusing the keys of the other kinds (the run's
/// `system.temperature`, particles and their material set its bounds and β).
fn wall_kind(
    wall: &WallSection,
    description: &RunDescription,
    species: &[Species],
    key: &dyn Fn(&str) -> String,
) -> Result<WallSpecKind> {
    let gas_temperature = description.system.temperature;
    let kind = wall.kind;
    let refuse = |name: &str, present: bool, for_kinds: &str| -> Result<()> {
        if present {
            Err(Error::input(
                key(name),
                format!(
                    "only for kind = {for_kinds}, not for kind = \"{}\"",
                    kind.name()
                ),
            ))
        } else {
            Ok(())
        }
    };
    let restitution_kinds = "\"restitution\" or \"vibrating\"";
    if !matches!(kind, WallKindName::Restitution | WallKindName::Vibrating) {
        refuse("restitution", wall.restitution.is_some(), restitution_kinds)?;
        for (name, present) in law_keys(wall) {
            refuse(name, present, restitution_kinds)?;
        }
    }
    if kind != WallKindName::Thermal {
        refuse("temperature", wall.temperature.is_some(), "\"thermal\"")?;
    }
    if kind != WallKindName::Vibrating {
        refuse("amplitude", wall.amplitude.is_some(), "\"vibrating\"")?;
        refuse("frequency", wall.frequency.is_some(), "\"vibrating\"")?;
        refuse("waveform", wall.waveform.is_some(), "\"vibrating\"")?;
    }
    match kind {
        WallKindName::Elastic => Ok(WallSpecKind::Elastic),
        WallKindName::Restitution => Ok(WallSpecKind::Restitution(wall_law(
            wall,
            key,
            description,
            species,
        )?)),
        WallKindName::Thermal => {
            let t = wall
                .temperature
                .ok_or_else(|| Error::input(key("temperature"), "missing for a thermal wall"))?;
            let (low, high) = (
                gas_temperature / WALL_TEMPERATURE_RATIO,
                gas_temperature * WALL_TEMPERATURE_RATIO,
            );
            if !(low..=high).contains(&t) {
                return Err(Error::out_of_range(
                    &key("temperature"),
                    t,
                    &format!(
                        "{} ..= {} (1e-12 to 1e12 times system.temperature)",
                        crate::output::number(low),
                        crate::output::number(high)
                    ),
                ));
            }
            Ok(WallSpecKind::Thermal(t))
        }
        WallKindName::Vibrating => {
            let law = wall_law(wall, key, description, species)?;
            let positive = |name: &str, x: Option<f64>| {
                let x = x.ok_or_else(|| Error::input(key(name), "missing for a vibrating wall"))?;
                if (1e-30..=1e30).contains(&x) {
                    Ok(x)
                } else {
                    Err(Error::out_of_range(
                        &key(name),
                        crate::output::number(x),
                        "1e-30 <= value <= 1e30",
                    ))
                }
            };
            let amplitude = positive("amplitude", wall.amplitude)?;
            let frequency = positive("frequency", wall.frequency)?;
            // The wall's top speed (sine: 2 pi A f) against the gas's thermal speed, as
            // for a thermal wall's temperature.
            let speed = std::f64::consts::TAU * amplitude * frequency;
            let thermal = gas_temperature.sqrt();
            let ratio = WALL_TEMPERATURE_RATIO.sqrt();
            if speed > ratio * thermal {
                return Err(Error::out_of_range(
                    &key("frequency"),
                    frequency,
                    &format!(
                        "a wall speed 2 pi A f up to 1e6 thermal speeds sqrt(system.temperature): \
                         f <= {}",
                        crate::output::number(
                            ratio * thermal / (std::f64::consts::TAU * amplitude)
                        )
                    ),
                ));
            }
            Ok(WallSpecKind::Vibrating {
                law,
                motion: gas::walls::Motion {
                    amplitude,
                    frequency,
                    waveform: match wall.waveform.unwrap_or(Waveform::Sine) {
                        Waveform::Sine => gas::walls::Waveform::Sine,
                        Waveform::Triangle => gas::walls::Waveform::Triangle,
                        Waveform::Sawtooth => gas::walls::Waveform::Sawtooth,
                    },
                },
            })
        }
    }
}

/// The law keys of a wall, and whether each is given.
fn law_keys(wall: &WallSection) -> [(&'static str, bool); 8] {
    [
        ("law", wall.law.is_some()),
        ("damping_ratio", wall.damping_ratio.is_some()),
        ("criterion", wall.criterion.is_some()),
        ("beta", wall.beta.is_some()),
        ("form", wall.form.is_some()),
        ("young", wall.young.is_some()),
        ("poisson", wall.poisson.is_some()),
        ("dissipative_constant", wall.dissipative_constant.is_some()),
    ]
}

/// β of a viscoelastic wall given by its material (instead of `beta`): a half-space of
/// the wall's `young`, `poisson`, `dissipative_constant` (each left out: the particles' of
/// `[collision]`; all left out: a wall of the particles' own material, as the soft-sphere
/// engine's walls), hit by the spheres of the one species of the run
/// ([`restitution::material::MaterialPair::wall_beta`]). A mixture's spheres would each
/// need their own β: refused, naming the key.
fn wall_material_beta(
    wall: &WallSection,
    key: &dyn Fn(&str) -> String,
    description: &RunDescription,
    species: &[Species],
) -> Result<f64> {
    let given = [
        ("young", wall.young),
        ("poisson", wall.poisson),
        ("dissipative_constant", wall.dissipative_constant),
    ];
    let named = given.iter().find(|g| g.1.is_some()).map_or("beta", |g| g.0);
    let particles = super::material::material(description)?.ok_or_else(|| {
        Error::input(
            key(named),
            "a wall's material needs the particles' (collision.young, poisson, \
             dissipative_constant, or collision.material); or give the wall's beta",
        )
    })?;
    if species.len() > 1 || description.system.species.is_some() {
        return Err(Error::input(
            key(named),
            "a wall's material with a mixture (a beta per species) is not built; give the \
             wall's beta",
        ));
    }
    let wall_material = (
        wall.young.unwrap_or(particles.young),
        wall.poisson.unwrap_or(particles.poisson),
        wall.dissipative_constant
            .unwrap_or(particles.dissipative_constant),
    );
    let sphere = (
        particles.young,
        particles.poisson,
        particles.dissipative_constant,
    );
    let pair = restitution::material::MaterialPair::new(sphere, wall_material).map_err(|e| {
        let name = match &e {
            restitution::Error::OutOfRange { name, .. } if name.contains("poisson") => "poisson",
            restitution::Error::OutOfRange { name, .. } if name.contains("dissipative") => {
                "dissipative_constant"
            }
            _ => "young",
        };
        Error::input(key(name), e)
    })?;
    let kind = &species[0];
    Ok(pair.wall_beta(kind.radius(), kind.mass))
}

/// The law of a restitution or vibrating wall: `law` (default constant) with its own keys
/// only.
fn wall_law(
    wall: &WallSection,
    key: &dyn Fn(&str) -> String,
    description: &RunDescription,
    species: &[Species],
) -> Result<WallLaw> {
    let law = wall.law.unwrap_or(LawKind::Constant);
    let own: &[&str] = match law {
        LawKind::Constant => &["restitution"],
        LawKind::Dashpot => &["damping_ratio", "criterion"],
        LawKind::Viscoelastic => &["beta", "form", "young", "poisson", "dissipative_constant"],
        LawKind::Stochastic => {
            return Err(Error::input(
                key("law"),
                "a wall has no internal modes; allowed: \"constant\", \"dashpot\", \
                 \"viscoelastic\"",
            ))
        }
    };
    let given = [("restitution", wall.restitution.is_some())]
        .into_iter()
        .chain(law_keys(wall).into_iter().skip(1));
    for (name, present) in given {
        if present && !own.contains(&name) {
            return Err(Error::input(
                key(name),
                format!(
                    "not a key of law = \"{}\" (its keys: {})",
                    law.name(),
                    own.join(", ")
                ),
            ));
        }
    }
    match law {
        LawKind::Dashpot => Ok(WallLaw::Dashpot {
            damping_ratio: wall.damping_ratio.ok_or_else(|| {
                Error::input(key("damping_ratio"), "missing for law = \"dashpot\"")
            })?,
            criterion: wall.criterion.unwrap_or(Criterion::Improved),
        }),
        LawKind::Viscoelastic => {
            let material = wall.young.is_some()
                || wall.poisson.is_some()
                || wall.dissipative_constant.is_some();
            let beta = match wall.beta {
                Some(_) if material => {
                    return Err(Error::input(
                        key("beta"),
                        "give the wall's beta or its material (young, poisson, \
                         dissipative_constant), not both",
                    ))
                }
                Some(beta) => beta,
                None => wall_material_beta(wall, key, description, species)?,
            };
            if !(beta.is_finite() && beta >= 0.0) {
                return Err(Error::out_of_range(
                    &key("beta"),
                    beta,
                    "a finite beta >= 0",
                ));
            }
            Ok(WallLaw::Viscoelastic {
                beta,
                form: wall.form.unwrap_or(FormName::Fast(Criterion::Improved)),
            })
        }
        _ => {
            let eps = wall.restitution.unwrap_or(1.0);
            if !(eps.is_finite() && (0.0..=1.0).contains(&eps)) {
                return Err(Error::out_of_range(&key("restitution"), eps, "0 <= e <= 1"));
            }
            Ok(WallLaw::Constant(eps))
        }
    }
}
