//! The runtime's typed errors: no heap in them, so that they exist without
//! `std` (a controller's forward dynamics can fail too).

use core::fmt;

use thiserror::Error;

/// What can go wrong when a generated model is evaluated at run time.
///
/// ```
/// use dynamics_runtime::DynamicsError;
/// let e = DynamicsError::NonFinite { quantity: "q", index: 2 };
/// assert_eq!(e.to_string(), "q[2] is not finite (NaN or infinite)");
/// ```
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DynamicsError {
    /// An input vector holds NaN or an infinity.
    #[error("{quantity}[{index}] is not finite (NaN or infinite)")]
    NonFinite {
        /// Which input (`q`, `qd`, `u`, ...).
        quantity: &'static str,
        /// Index of the first offending entry.
        index: usize,
    },
    /// The inertia matrix A(q) is not positive definite at this configuration,
    /// so the accelerations cannot be solved for.
    #[error("the inertia matrix A(q) is not positive definite at q = {q:?}")]
    SingularMassMatrix {
        /// The configuration at which the factorisation failed.
        q: Coordinates,
    },
    /// A computed quantity came out NaN or infinite although the inputs were finite.
    #[error("{quantity}[{index}] came out NaN or infinite")]
    Diverged {
        /// Which output.
        quantity: &'static str,
        /// Index of the first offending entry.
        index: usize,
    },
    /// An output slice does not have the length the robot needs.
    #[error("{quantity} needs a slice of length {expected}, got {found}")]
    Length {
        /// Which output (`inertial_regressor`, ...).
        quantity: &'static str,
        /// The length it needs (e.g. `Robot::LINK_NAMES.len()`).
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// No run-time parameter of this robot has that name.
    #[error("unknown parameter `{name}`; this robot has: {}", Joined(.known))]
    UnknownParameter {
        /// The name asked for.
        name: ParameterName,
        /// The names the robot has ([`Parameters::NAMES`](crate::Parameters::NAMES)).
        known: &'static [&'static str],
    },
}

/// Joint coordinates as an error carries them, without the heap: the first
/// [`Coordinates::CAPACITY`] values and how many there were. Its `Debug`
/// form is that of the slice (`[0.1, -0.2]`), with `..., (n in all)` after
/// the kept values of a longer one.
///
/// ```
/// use dynamics_runtime::Coordinates;
/// let q = Coordinates::new(&[0.5, -1.0]);
/// assert_eq!((q.kept(), q.len()), (&[0.5, -1.0][..], 2));
/// assert_eq!(format!("{q:?}"), "[0.5, -1.0]");
/// let long = Coordinates::new(&[1.0; 10]);
/// assert_eq!(long.kept().len(), Coordinates::CAPACITY);
/// assert!(format!("{long:?}").ends_with("1.0, ..., (10 in all)]"));
/// ```
#[derive(Clone, Copy, PartialEq)]
pub struct Coordinates {
    values: [f64; Coordinates::CAPACITY],
    len: usize,
}

impl Coordinates {
    /// How many values are kept: enough for a 7-axis arm and its gripper,
    /// few enough that an error stays small (clippy's `result_large_err`
    /// draws the line at 128 bytes, and results carry it on every call).
    pub const CAPACITY: usize = 8;

    /// The first [`Coordinates::CAPACITY`] values of `q`, and its length.
    pub fn new(q: &[f64]) -> Self {
        let mut values = [0.0; Self::CAPACITY];
        for (v, x) in values.iter_mut().zip(q) {
            *v = *x;
        }
        Self {
            values,
            len: q.len(),
        }
    }

    /// The values kept (all of them up to [`Coordinates::CAPACITY`]).
    pub fn kept(&self) -> &[f64] {
        &self.values[..self.len.min(Self::CAPACITY)]
    }

    /// How many coordinates there were.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there were none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl fmt::Debug for Coordinates {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.len <= Self::CAPACITY {
            return fmt::Debug::fmt(self.kept(), f);
        }
        f.write_str("[")?;
        for v in self.kept() {
            fmt::Debug::fmt(v, f)?;
            f.write_str(", ")?;
        }
        write!(f, "..., ({} in all)]", self.len)
    }
}

/// A parameter name as an error carries it, without the heap: up to
/// [`ParameterName::CAPACITY`] bytes of it (cut at a character boundary,
/// and then shown with `...` after it).
///
/// ```
/// use dynamics_runtime::ParameterName;
/// assert_eq!(ParameterName::new("payload").to_string(), "payload");
/// let long = ParameterName::new(&"x".repeat(40));
/// assert_eq!(long.as_str().len(), ParameterName::CAPACITY);
/// assert!(long.to_string().ends_with("x..."));
/// ```
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct ParameterName {
    bytes: [u8; ParameterName::CAPACITY],
    len: u8,
    cut: bool,
}

impl ParameterName {
    /// Bytes kept.
    pub const CAPACITY: usize = 32;

    /// `name`, or as much of it as fits.
    pub fn new(name: &str) -> Self {
        let mut end = name.len().min(Self::CAPACITY);
        while !name.is_char_boundary(end) {
            end -= 1;
        }
        let mut bytes = [0; Self::CAPACITY];
        bytes[..end].copy_from_slice(&name.as_bytes()[..end]);
        Self {
            bytes,
            len: end as u8,
            cut: end < name.len(),
        }
    }

    /// The name kept.
    pub fn as_str(&self) -> &str {
        // Cut at a character boundary of a `str`: always UTF-8.
        core::str::from_utf8(&self.bytes[..usize::from(self.len)]).unwrap_or_default()
    }

    /// Whether the name was longer than what is kept.
    pub fn is_cut(&self) -> bool {
        self.cut
    }
}

impl fmt::Display for ParameterName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())?;
        if self.cut {
            f.write_str("...")?;
        }
        Ok(())
    }
}

impl fmt::Debug for ParameterName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.as_str(), f)?;
        if self.cut {
            f.write_str("...")?;
        }
        Ok(())
    }
}

/// Names, comma separated; `(none)` for none.
struct Joined<'a>(&'a [&'static str]);

impl fmt::Display for Joined<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return f.write_str("(none)");
        }
        for (i, name) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            f.write_str(name)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_read_as_with_owned_strings() {
        let e = DynamicsError::SingularMassMatrix {
            q: Coordinates::new(&[0.1, -0.25, 3.0]),
        };
        assert_eq!(
            e.to_string(),
            "the inertia matrix A(q) is not positive definite at q = [0.1, -0.25, 3.0]"
        );
        let e = DynamicsError::UnknownParameter {
            name: ParameterName::new("mass"),
            known: &["m", "payload"],
        };
        assert_eq!(
            e.to_string(),
            "unknown parameter `mass`; this robot has: m, payload"
        );
        let e = DynamicsError::UnknownParameter {
            name: ParameterName::new("m"),
            known: &[],
        };
        assert_eq!(
            e.to_string(),
            "unknown parameter `m`; this robot has: (none)"
        );
    }

    #[test]
    fn long_values_are_cut_and_say_so() {
        let q: Vec<f64> = (0..12).map(f64::from).collect();
        let c = Coordinates::new(&q);
        assert_eq!(c.len(), 12);
        assert_eq!(c.kept(), &q[..8]);
        assert_eq!(
            format!("{c:?}"),
            "[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, ..., (12 in all)]"
        );
        assert!(Coordinates::new(&[]).is_empty());
        // A multi-byte character across the limit is dropped whole.
        let name = format!("{}é", "a".repeat(31));
        let n = ParameterName::new(&name);
        assert_eq!(n.as_str(), "a".repeat(31));
        assert!(n.is_cut());
        assert_eq!(format!("{n:?}"), format!("\"{}\"...", "a".repeat(31)));
        assert!(!ParameterName::new(&"b".repeat(32)).is_cut());
    }

    #[test]
    fn the_error_stays_small() {
        // What every `Result<_, DynamicsError>` carries.
        assert!(core::mem::size_of::<DynamicsError>() <= 96);
    }
}
