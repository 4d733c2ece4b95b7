//! The [`Restitution`] trait through which engines obtain eps at each collision, and its
//! implementations: constant, dash-pot and the viscoelastic laws.

use crate::bucket::BucketTable;
use crate::dashpot::{dashpot, DashpotCriterion};
use crate::error::{require_positive, Error, Result};
use crate::exact::{self, Criterion};
use crate::fast::Fast;
use crate::material::ContactPair;
use crate::pade::Pade;
use crate::series::Series;
use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

/// A coefficient-of-restitution law: eps as a function of the normal impact speed.
///
/// Implementations are immutable, thread-safe, cheap to clone and allocate nothing per call.
pub trait Restitution: Send + Sync + fmt::Debug {
    /// eps for a collision with normal impact speed `speed` >= 0, in the law's units.
    fn eps(&self, speed: f64) -> f64;
    /// The collision duration in the law's time unit, where the law knows it.
    fn duration(&self, _speed: f64) -> Option<f64> {
        None
    }
    /// A short description, e.g. `viscoelastic fast (beta = 0.1)`.
    fn describe(&self) -> String;
    /// A boxed copy (for `Clone` on `Box<dyn Restitution>`).
    fn box_clone(&self) -> Box<dyn Restitution>;
    /// The stochastic side of laws whose eps is random and feeds internal baths (Giese);
    /// `None` for deterministic laws.
    fn stochastic(&self) -> Option<&dyn crate::stochastic::StochasticRestitution> {
        None
    }
    /// The laws per pair of particle kinds of a mixture whose pairs collide differently
    /// ([`crate::pairwise::Pairwise`]); `None` for one law for all pairs.
    fn pairwise(&self) -> Option<&crate::pairwise::Pairwise> {
        None
    }
    /// The tangential rule of rough spheres ([`crate::rough::Rough`]); `None` for smooth
    /// spheres.
    fn tangential(&self) -> Option<&crate::rough::Tangential> {
        None
    }
    /// A tangential rule per pair of particle kinds ([`crate::rough::TangentialPairs`]);
    /// `None`: [`Restitution::tangential`] for every pair.
    fn tangential_pairs(&self) -> Option<&crate::rough::TangentialPairs> {
        None
    }
}

impl Clone for Box<dyn Restitution> {
    fn clone(&self) -> Self {
        self.box_clone()
    }
}

/// A velocity-independent coefficient of restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constant {
    eps: f64,
}

impl Constant {
    pub fn new(eps: f64) -> Result<Self> {
        if eps.is_finite() && (0.0..=1.0).contains(&eps) {
            Ok(Constant { eps })
        } else {
            Err(Error::out_of_range("restitution", eps, "0 <= eps <= 1"))
        }
    }
}

impl Restitution for Constant {
    fn eps(&self, _speed: f64) -> f64 {
        self.eps
    }
    fn describe(&self) -> String {
        format!("constant (eps = {})", self.eps)
    }
    fn box_clone(&self) -> Box<dyn Restitution> {
        Box::new(*self)
    }
}

/// The linear dash-pot (Eqs. 10 and 12 of SP2008): eps independent of speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dashpot {
    ratio: f64,
    criterion: DashpotCriterion,
    eps: f64,
    /// omega_0 t_c and omega_0, if known, for the physical duration.
    scaled_duration: f64,
    omega0: Option<f64>,
}

impl Dashpot {
    /// From the damping ratio R = b/omega_0 (b = gamma/(2 m_eff)).
    pub fn new(ratio: f64, criterion: DashpotCriterion, omega0: Option<f64>) -> Result<Self> {
        if let Some(w) = omega0 {
            require_positive("omega0", w)?;
        }
        let outcome = dashpot(ratio, criterion)?;
        Ok(Dashpot {
            ratio,
            criterion,
            eps: outcome.eps,
            scaled_duration: outcome.scaled_duration,
            omega0,
        })
    }
}

impl Restitution for Dashpot {
    fn eps(&self, _speed: f64) -> f64 {
        self.eps
    }
    fn duration(&self, _speed: f64) -> Option<f64> {
        self.omega0.map(|w| self.scaled_duration / w)
    }
    fn describe(&self) -> String {
        format!(
            "dashpot {:?} (damping ratio = {})",
            self.criterion, self.ratio
        )
    }
    fn box_clone(&self) -> Box<dyn Restitution> {
        Box::new(*self)
    }
}

/// How a viscoelastic law computes eps(v*).
#[derive(Debug, Clone)]
pub enum ScaledForm {
    /// Integration of Eq. (9) of MP2011 with the given end-of-collision criterion.
    Exact(Criterion),
    /// A Padé approximant (Eq. 11 of MP2011).
    Pade(Pade),
    /// The truncated series (Eq. 7 of MP2011).
    Series(Series),
    /// The tabulated exact law of [`crate::fast`].
    Fast(Fast),
}

impl ScaledForm {
    /// eps at scaled impact speed v* >= 0.
    #[inline]
    pub fn eps(&self, vstar: f64) -> f64 {
        match self {
            ScaledForm::Exact(c) => exact_or_asymptotic(vstar, *c),
            ScaledForm::Pade(p) => p.eval(vstar),
            ScaledForm::Series(s) => s.eval(vstar),
            ScaledForm::Fast(f) => f.eval(vstar),
        }
    }

    /// eps at every scaled speed of `vstar` into `out` (of the same length): the form is
    /// matched once and its evaluator inlined into the loop, several times faster than
    /// calling [`ScaledForm::eps`] per value for the fast law (bit-identical to it).
    pub fn eps_slice(&self, vstar: &[f64], out: &mut [f64]) {
        assert_eq!(vstar.len(), out.len(), "eps_slice: lengths differ");
        if let ScaledForm::Fast(f) = self {
            return f.eval_slice(vstar, out);
        }
        let pairs = out.iter_mut().zip(vstar);
        match self {
            ScaledForm::Fast(f) => f.eval_slice(vstar, out),
            ScaledForm::Pade(p) => pairs.for_each(|(o, &v)| *o = p.eval(v)),
            ScaledForm::Series(s) => pairs.for_each(|(o, &v)| *o = s.eval(v)),
            ScaledForm::Exact(c) => pairs.for_each(|(o, &v)| *o = exact_or_asymptotic(v, *c)),
        }
    }

    /// Scaled collision duration tau_c, known to the exact forms.
    pub fn duration(&self, vstar: f64) -> Option<f64> {
        match self {
            ScaledForm::Exact(c) => exact::solve(vstar, *c).ok().map(|col| col.duration),
            _ => None,
        }
    }
}

/// The exact law; beyond its validated range (v* > 1e6) the asymptotic power law of the
/// fast law is used instead of failing.
fn exact_or_asymptotic(vstar: f64, criterion: Criterion) -> f64 {
    match exact::solve(vstar, criterion) {
        Ok(c) => c.eps,
        Err(_) => Fast::new(criterion).eval(vstar),
    }
}

impl fmt::Display for ScaledForm {
    /// The name that [`ScaledForm::from_str`] parses back.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let naive = |c: &Criterion| if *c == Criterion::Naive { "-naive" } else { "" };
        match self {
            ScaledForm::Exact(c) => write!(f, "exact{}", naive(c)),
            ScaledForm::Fast(x) => write!(f, "fast{}", naive(&x.criterion())),
            ScaledForm::Pade(p) => {
                let kind = if p.is_from_paper() {
                    "pade-paper"
                } else {
                    "pade"
                };
                write!(f, "{kind}:{}/{}", p.orders().0, p.orders().1)
            }
            ScaledForm::Series(s) if s.is_from_paper() => write!(f, "series-paper:{}", s.order()),
            ScaledForm::Series(s) => write!(f, "series:{}", s.order()),
        }
    }
}

impl FromStr for ScaledForm {
    type Err = Error;
    /// `exact`, `exact-naive`, `fast`, `fast-naive`, `pade:M/N`, `series:K` (coefficients
    /// computed by `haff-series`), `pade-paper:M/N`, `series-paper:K` (printed in the papers).
    fn from_str(s: &str) -> Result<Self> {
        s.parse::<FormName>()?.build()
    }
}

/// Where the coefficients of a Padé or series form come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Coefficients {
    /// Computed by `haff-series` to any order.
    Computed,
    /// Printed in the papers (Table I of MP2011, Table V of SP2008).
    Paper,
}

/// The name of a [`ScaledForm`], parsed but not built (building a Padé approximant or the
/// fast table takes time): what a run description stores. Displays as the name it parses
/// from, and serializes as that string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FormName {
    Exact(Criterion),
    Fast(Criterion),
    Pade {
        m: usize,
        n: usize,
        coefficients: Coefficients,
    },
    Series {
        order: usize,
        coefficients: Coefficients,
    },
}

impl FormName {
    /// Builds the form (fails for orders the coefficients do not provide).
    pub fn build(&self) -> Result<ScaledForm> {
        Ok(match *self {
            FormName::Exact(c) => ScaledForm::Exact(c),
            FormName::Fast(c) => ScaledForm::Fast(Fast::new(c)),
            FormName::Pade { m, n, coefficients } => ScaledForm::Pade(match coefficients {
                Coefficients::Computed => Pade::computed(m, n)?,
                Coefficients::Paper => Pade::table_i(m, n)?,
            }),
            FormName::Series {
                order,
                coefficients,
            } => ScaledForm::Series(match coefficients {
                Coefficients::Computed => Series::computed(order)?,
                Coefficients::Paper => Series::table_v(order)?,
            }),
        })
    }
}

impl fmt::Display for FormName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let naive = |c: &Criterion| if *c == Criterion::Naive { "-naive" } else { "" };
        let paper = |c: &Coefficients| match c {
            Coefficients::Computed => "",
            Coefficients::Paper => "-paper",
        };
        match self {
            FormName::Exact(c) => write!(f, "exact{}", naive(c)),
            FormName::Fast(c) => write!(f, "fast{}", naive(c)),
            FormName::Pade { m, n, coefficients } => {
                write!(f, "pade{}:{m}/{n}", paper(coefficients))
            }
            FormName::Series {
                order,
                coefficients,
            } => write!(f, "series{}:{order}", paper(coefficients)),
        }
    }
}

impl FromStr for FormName {
    type Err = Error;
    /// `exact`, `exact-naive`, `fast`, `fast-naive`, `pade:M/N`, `series:K`,
    /// `pade-paper:M/N`, `series-paper:K`.
    fn from_str(s: &str) -> Result<Self> {
        let bad = |m: &str| Error::parse("law", format!("'{s}': {m}"));
        match s {
            "exact" => return Ok(FormName::Exact(Criterion::Improved)),
            "exact-naive" => return Ok(FormName::Exact(Criterion::Naive)),
            "fast" => return Ok(FormName::Fast(Criterion::Improved)),
            "fast-naive" => return Ok(FormName::Fast(Criterion::Naive)),
            _ => {}
        }
        let series = |order: &str, coefficients| {
            let order = order
                .parse()
                .map_err(|_| bad("series:K needs an integer K"))?;
            Ok(FormName::Series {
                order,
                coefficients,
            })
        };
        if let Some(order) = s.strip_prefix("series-paper:") {
            return series(order, Coefficients::Paper);
        }
        if let Some(order) = s.strip_prefix("series:") {
            return series(order, Coefficients::Computed);
        }
        let pade = |text: &str, coefficients| {
            text.split_once('/')
                .and_then(|(m, n)| Some((m.parse().ok()?, n.parse().ok()?)))
                .map(|(m, n)| FormName::Pade { m, n, coefficients })
                .ok_or_else(|| bad("pade:M/N needs integers M and N"))
        };
        if let Some(text) = s.strip_prefix("pade-paper:") {
            return pade(text, Coefficients::Paper);
        }
        if let Some(text) = s.strip_prefix("pade:") {
            return pade(text, Coefficients::Computed);
        }
        Err(bad(
            "allowed: exact, exact-naive, fast, fast-naive, pade:M/N, pade-paper:M/N, series:K, series-paper:K",
        ))
    }
}

impl serde::Serialize for FormName {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> serde::Deserialize<'de> for FormName {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

/// A viscoelastic law in physical units: v* = beta^(1/2) v^(1/10) (Eq. 7 of MP2011).
///
/// With the fast form, eps is also tabulated directly in v (binary buckets, two per octave
/// of v, about 50 KB shared by clones), so that a call costs no power v^(1/10).
#[derive(Debug, Clone)]
pub struct Viscoelastic {
    beta: f64,
    speed_table: Option<Arc<BucketTable>>,
    /// (rho/m_eff)^(-2/5): the time unit of Eq. (9) is this times v^(-1/5).
    time_unit: Option<f64>,
    form: ScaledForm,
}

impl Viscoelastic {
    /// A law with material constant beta (units (time/length)^(1/5), consistent with the
    /// speeds passed to `eps`).
    pub fn new(beta: f64, form: ScaledForm) -> Result<Self> {
        require_positive("beta", beta)?;
        let speed_table = match &form {
            ScaledForm::Fast(fast) => Some(Arc::new(speed_table(beta, *fast))),
            _ => None,
        };
        Ok(Viscoelastic {
            beta,
            speed_table,
            time_unit: None,
            form,
        })
    }

    /// The law of a contact pair in SI units: beta (Eq. 8 of MP2011) and k = rho/m_eff
    /// (Eq. 18 of SP2008) from the material and the spheres; speeds in m/s, time in s.
    pub fn for_pair(pair: &ContactPair, form: ScaledForm) -> Result<Self> {
        Viscoelastic::new(pair.beta()?, form)?.with_k(pair.k())
    }

    /// Adds k = rho/m_eff (Eq. 18 of SP2008) so that `duration` is known in physical time.
    pub fn with_k(mut self, k: f64) -> Result<Self> {
        self.time_unit = Some(require_positive("k", k)?.powf(-0.4));
        Ok(self)
    }

    pub fn beta(&self) -> f64 {
        self.beta
    }

    pub fn form(&self) -> &ScaledForm {
        &self.form
    }

    /// v* = beta^(1/2) v^(1/10).
    #[inline]
    pub fn vstar(&self, speed: f64) -> f64 {
        self.beta.sqrt() * speed.powf(0.1)
    }
}

impl Restitution for Viscoelastic {
    #[inline]
    fn eps(&self, speed: f64) -> f64 {
        match &self.speed_table {
            Some(table) if table.contains(speed) => table.eval(speed),
            _ => self.form.eps(self.vstar(speed)),
        }
    }

    fn duration(&self, speed: f64) -> Option<f64> {
        let tau = self.form.duration(self.vstar(speed))?;
        Some(tau * self.time_unit? * speed.powf(-0.2))
    }

    fn describe(&self) -> String {
        format!("viscoelastic {} (beta = {})", self.form, self.beta)
    }

    fn box_clone(&self) -> Box<dyn Restitution> {
        Box::new(self.clone())
    }
}

/// The fast law tabulated in the physical speed v over the range that maps to the fast
/// table's v* range, v = v*^10 / beta^5.
fn speed_table(beta: f64, fast: Fast) -> BucketTable {
    use crate::fast::{VSTAR_MAX, VSTAR_MIN};
    let log2_v = |vstar: f64| 10.0 * vstar.log2() - 5.0 * beta.log2();
    let lo = (log2_v(VSTAR_MIN).ceil() as i32).clamp(-1021, 1021);
    let hi = (log2_v(VSTAR_MAX).floor() as i32).clamp(lo + 1, 1022);
    let root_beta = beta.sqrt();
    BucketTable::new(lo, hi, 1, |v| fast.eval(root_beta * v.powf(0.1)))
}
