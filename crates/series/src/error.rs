//! The error type of the crate: every message names the offending input and what is allowed.

use crate::coefficients::Kind;
use crate::pade::PadeError;

/// Why the crate refused an input.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// A coefficient family other than those of [`Kind::ALL`] (h, c, a, b).
    #[error(
        "unknown coefficient kind '{given}' (allowed: {allowed})",
        allowed = Kind::ALL.map(Kind::name).join(", ")
    )]
    UnknownKind { given: String },
    /// More coefficients asked for than the chain's settings provide.
    #[error("index {order} is beyond what the chain provides (0..{provided})")]
    OrderBeyondChain { order: usize, provided: usize },
    /// A Padé approximant that cannot be built ([`crate::pade::pade`]).
    #[error(transparent)]
    Pade(#[from] PadeError),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_kind_names_the_input_and_the_allowed_kinds() {
        let err = "z".parse::<Kind>().unwrap_err();
        assert_eq!(
            err,
            Error::UnknownKind {
                given: "z".to_string()
            }
        );
        assert_eq!(
            err.to_string(),
            "unknown coefficient kind 'z' (allowed: h, c, a, b)"
        );
        for kind in Kind::ALL {
            assert_eq!(kind.name().parse::<Kind>(), Ok(kind));
        }
    }
}
