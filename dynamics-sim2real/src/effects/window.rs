//! The time window of an effect that starts and stops: an encoder that
//! slips at t0 and keeps its offset, a tool inside a medium, a payload
//! picked up and put down.

use thiserror::Error;

/// A half-open time span `[start, end)` in seconds from the record's first
/// sample; `end` may be infinite (on until the end of the record).
///
/// ```
/// use dynamics_sim2real::effects::Window;
/// let slip: Window = "2.5:".parse().unwrap(); // from 2.5 s to the end
/// assert!(!slip.contains(2.4) && slip.contains(2.5) && slip.contains(1e9));
/// let held: Window = "1:3".parse().unwrap();
/// assert!(held.contains(1.0) && !held.contains(3.0));
/// assert_eq!(held.clipped(2.0).end, 2.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Start, s.
    pub start: f64,
    /// End, s (exclusive; infinite: to the end of the record).
    pub end: f64,
}

/// Why a window could not be read or used.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WindowError {
    /// The text is not `START:END`.
    #[error("window `{text}`: expected START:END in seconds (END may be left out: to the end of the record)")]
    Syntax {
        /// The text given.
        text: String,
    },
    /// The bounds are not a span.
    #[error("window [{start}, {end}): start must be finite and >= 0, and end > start")]
    Empty {
        /// Start given.
        start: f64,
        /// End given.
        end: f64,
    },
}

impl Window {
    /// Whether time `t` lies inside.
    pub fn contains(&self, t: f64) -> bool {
        t >= self.start && t < self.end
    }

    /// The window with its end at most `end` (an open end becomes the
    /// record's end).
    pub fn clipped(&self, end: f64) -> Window {
        Window {
            start: self.start,
            end: self.end.min(end),
        }
    }

    /// The window moved by `dt` seconds (an open end stays open; the start
    /// stays >= 0).
    pub fn shifted(&self, dt: f64) -> Window {
        Window {
            start: (self.start + dt).max(0.0),
            end: self.end + dt,
        }
    }

    /// Checks the bounds.
    pub fn validate(&self) -> Result<(), WindowError> {
        if self.start.is_finite() && self.start >= 0.0 && self.end > self.start {
            Ok(())
        } else {
            Err(WindowError::Empty {
                start: self.start,
                end: self.end,
            })
        }
    }
}

impl std::str::FromStr for Window {
    type Err = WindowError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let syntax = || WindowError::Syntax { text: s.into() };
        let (a, b) = s.split_once(':').ok_or_else(syntax)?;
        let start: f64 = a.trim().parse().map_err(|_| syntax())?;
        let end: f64 = match b.trim() {
            "" | "end" => f64::INFINITY,
            b => b.parse().map_err(|_| syntax())?,
        };
        let w = Window { start, end };
        w.validate()?;
        Ok(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_windows_are_refused_with_the_text() {
        let e = "3".parse::<Window>().unwrap_err();
        assert!(e.to_string().contains("window `3`"), "{e}");
        assert!(matches!(
            "4:2".parse::<Window>(),
            Err(WindowError::Empty { .. })
        ));
        assert!("-1:2".parse::<Window>().is_err());
        assert_eq!(
            "1:end".parse::<Window>().unwrap().shifted(-0.5),
            Window {
                start: 0.5,
                end: f64::INFINITY
            }
        );
    }
}
