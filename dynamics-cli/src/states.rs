//! States files: the JSON format of `shared/reference/pinocchio/*.json`
//! (each state's `q`, `v`, `a`; other fields are ignored when read).

use serde_json::Value;
use thiserror::Error;

/// One state: position, velocity, acceleration.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Joint positions.
    pub q: Vec<f64>,
    /// Joint velocities.
    pub v: Vec<f64>,
    /// Joint accelerations.
    pub a: Vec<f64>,
}

/// Why a states file could not be read.
#[derive(Debug, Error)]
pub enum StatesError {
    /// Not JSON at all.
    #[error("{file}: not valid JSON: {source}")]
    Json {
        /// The file.
        file: String,
        /// The parser's error (with line and column).
        source: serde_json::Error,
    },
    /// JSON, but not of the expected shape.
    #[error("{file}: {place}: {problem}")]
    Shape {
        /// The file.
        file: String,
        /// Where in the document, e.g. `states[3].q`.
        place: String,
        /// What is wrong there.
        problem: String,
    },
}

/// Reads the `states` array of a document; every state must have `q`, `v`
/// and `a` of length `n` made of finite numbers.
///
/// ```
/// let doc = r#"{"states": [{"q": [0.1], "v": [0.0], "a": [1.0]}]}"#;
/// let s = dynamics_cli::states::parse(doc, "inline", 1).unwrap();
/// assert_eq!(s[0].a, vec![1.0]);
/// assert!(dynamics_cli::states::parse(doc, "inline", 2).is_err());
/// ```
pub fn parse(text: &str, file: &str, n: usize) -> Result<Vec<State>, StatesError> {
    let doc: Value = serde_json::from_str(text).map_err(|source| StatesError::Json {
        file: file.to_string(),
        source,
    })?;
    let shape = |place: String, problem: String| StatesError::Shape {
        file: file.to_string(),
        place,
        problem,
    };
    let states = doc.get("states").and_then(Value::as_array).ok_or_else(|| {
        shape(
            "top level".into(),
            "expected an array field `states`".into(),
        )
    })?;
    let mut out = Vec::with_capacity(states.len());
    for (k, s) in states.iter().enumerate() {
        let field = |name: &str| -> Result<Vec<f64>, StatesError> {
            let place = format!("states[{k}].{name}");
            let arr = s
                .get(name)
                .and_then(Value::as_array)
                .ok_or_else(|| shape(place.clone(), "missing, or not an array".into()))?;
            if arr.len() != n {
                return Err(shape(
                    place,
                    format!("has {} entries; this robot has {n} joints", arr.len()),
                ));
            }
            arr.iter()
                .enumerate()
                .map(|(i, x)| {
                    x.as_f64()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| shape(format!("{place}[{i}]"), "not a finite number".into()))
                })
                .collect()
        };
        out.push(State {
            q: field("q")?,
            v: field("v")?,
            a: field("a")?,
        });
    }
    Ok(out)
}
