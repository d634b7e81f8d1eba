//! The one error type of the engine. Bad user input always comes back as an `Err`, never a
//! panic: a measuring tool must tell its user which parameter is wrong and what it accepts.

/// Everything that can go wrong before or during one impact.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter is outside the range the model accepts. Worded like polars:
    /// "require `mu` >= 0 (found -1)".
    #[error("require `{name}` {expected} (found {value})")]
    InvalidParameter {
        /// The parameter's public name (as in the Python API).
        name: String,
        /// The offending value, formatted.
        value: String,
        /// The allowed range, in words ("> 0", "in (0, 90]").
        expected: String,
    },
    /// The run was interrupted through its [`Cancel`](crate::cancel::Cancel) token (Ctrl-C): no
    /// record, the impact was abandoned part-way.
    #[error("interrupted")]
    Interrupted,
}

/// Result alias used across the crate.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Builds an [`Error::InvalidParameter`].
    pub fn invalid(
        name: impl Into<String>,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        Error::InvalidParameter {
            name: name.into(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }

    /// The same error about the parameter `name` (a rule written for the particle, applied
    /// to the partner's `partner_*` column).
    pub(crate) fn renamed(self, name: &str) -> Self {
        match self {
            Error::InvalidParameter {
                value, expected, ..
            } => Error::InvalidParameter {
                name: name.to_string(),
                value,
                expected,
            },
            other => other,
        }
    }
}

/// Returns `Err(Error::InvalidParameter)` unless the condition holds.
macro_rules! ensure_param {
    ($cond:expr, $name:expr, $value:expr, $expected:expr $(,)?) => {
        if !($cond) {
            return Err($crate::error::Error::invalid($name, $value, $expected));
        }
    };
}
pub(crate) use ensure_param;

/// Checks that a value is finite and strictly positive.
pub(crate) fn positive(name: &str, value: f64) -> Result<()> {
    ensure_param!(
        value.is_finite() && value > 0.0,
        name,
        value,
        "finite and > 0"
    );
    Ok(())
}

/// Checks that a value is finite and not negative.
pub(crate) fn non_negative(name: &str, value: f64) -> Result<()> {
    ensure_param!(
        value.is_finite() && value >= 0.0,
        name,
        value,
        "finite and >= 0"
    );
    Ok(())
}

/// Checks that a value is finite.
pub(crate) fn finite(name: &str, value: f64) -> Result<()> {
    ensure_param!(value.is_finite(), name, value, "finite");
    Ok(())
}
