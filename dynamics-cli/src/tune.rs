//! The nominal model a subcommand starts from: run-time parameters set by
//! name (`--set NAME=VALUE`) and a calibrated baseline (`--baseline
//! FILE.json`: the effects of a previous diagnosis report).

use std::path::{Path, PathBuf};

use clap::Args;

use dynamics_runtime::{Parameters, Robot};
use dynamics_sim2real::baseline::{self, BaselineError, Entry};
use dynamics_sim2real::diagnose::{CalibrationSpread, Parameter};
use dynamics_sim2real::effects::{Calibrated, Effect, Window};
use serde_json::Value;
use thiserror::Error;

/// The model every subcommand on a robot starts from.
#[derive(Args, Debug, Clone, Default)]
pub struct ModelArgs {
    /// Set a run-time parameter of the nominal model, e.g. `--set c=0` (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
}

/// A calibrated baseline added to the nominal model.
#[derive(Args, Debug, Clone, Default)]
pub struct BaselineArgs {
    /// The effects of a previous diagnosis (its JSON report, `which.effects`), or a file
    /// `{"effects": [{"kind", "joint", "parameters": [{"name", "value"}]}]}`, added to the nominal model.
    #[arg(long, value_name = "FILE.json")]
    pub baseline: Option<PathBuf>,
}

/// Why the nominal model could not be made.
#[derive(Debug, Error)]
pub enum TuneError {
    /// `--set` not of the form NAME=VALUE, or VALUE not a finite number.
    #[error("--set `{arg}`: {problem}")]
    Set {
        /// The argument as given.
        arg: String,
        /// What is wrong with it.
        problem: String,
    },
    /// No parameter of that name.
    #[error("--set `{arg}`: the robot has no parameter `{name}`; known: {known}")]
    UnknownParameter {
        /// The argument as given.
        arg: String,
        /// The name.
        name: String,
        /// The robot's parameters.
        known: String,
    },
    /// The baseline file could not be read.
    #[error("--baseline {file}: {source}")]
    Read {
        /// The file.
        file: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The baseline file is not JSON.
    #[error("--baseline {file}: not valid JSON: {source}")]
    Json {
        /// The file.
        file: String,
        /// The parser's error (line and column).
        source: serde_json::Error,
    },
    /// JSON, but no effects where they belong.
    #[error("--baseline {file}: {place}: {problem}")]
    Shape {
        /// The file.
        file: String,
        /// Where in the document.
        place: String,
        /// What is wrong there.
        problem: String,
    },
    /// An entry that is no effect of this robot.
    #[error("--baseline {file}: {place}: {source}")]
    Effect {
        /// The file.
        file: String,
        /// Where in the document, e.g. `which.effects[1]`.
        place: String,
        /// The cause.
        source: Box<BaselineError>,
    },
}

/// Sets the run-time parameters `set` (each `NAME=VALUE`) on `robot`.
///
/// ```
/// use dynamics_runtime::{Parameters, Robot};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0]; param m = 1.0;
///     link base; link rod { mass = m; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let mut p = Pendulum::default();
/// dynamics_cli::tune::apply_set(&mut p, &["m=2.5".to_string()]).unwrap();
/// assert_eq!(p.params().get("m"), Some(2.5));
/// let err = dynamics_cli::tune::apply_set(&mut p, &["mass=1".to_string()]).unwrap_err();
/// assert_eq!(err.to_string(), "--set `mass=1`: the robot has no parameter `mass`; known: m");
/// assert!(dynamics_cli::tune::apply_set(&mut p, &["m=inf".to_string()]).is_err());
/// ```
pub fn apply_set<R: Robot<N>, const N: usize>(
    robot: &mut R,
    set: &[String],
) -> Result<(), TuneError> {
    for arg in set {
        let bad = |problem: String| TuneError::Set {
            arg: arg.clone(),
            problem,
        };
        let (name, value) = arg
            .split_once('=')
            .ok_or_else(|| bad("expected NAME=VALUE".into()))?;
        let (name, value) = (name.trim(), value.trim());
        let v: f64 = value
            .parse()
            .map_err(|_| bad(format!("`{value}` is not a number")))?;
        if !v.is_finite() {
            return Err(bad(format!("`{value}` is not a finite number")));
        }
        if robot.params_mut().set(name, v).is_err() {
            let names = <R::Params as Parameters>::NAMES;
            return Err(TuneError::UnknownParameter {
                arg: arg.clone(),
                name: name.to_string(),
                known: if names.is_empty() {
                    "(none)".into()
                } else {
                    names.join(", ")
                },
            });
        }
    }
    Ok(())
}

/// The effects of the baseline file `path` for robot `R`: the report's
/// `which.effects[]` (or a top-level `effects[]`), else the effect its
/// `which.verdict` names, with the parameters of the matching entry of
/// `which.ranked[]`. A verdict that names no effect is an empty baseline.
/// An entry limited in time (`window`) is refused here (the effects of
/// `simulate --effects` are on all the time); [`read_baseline_timed`]
/// keeps it with its window.
pub fn read_baseline<R: Robot<N>, const N: usize>(path: &Path) -> Result<Vec<Effect>, TuneError> {
    let (file, text) = read(path)?;
    baseline_from_str::<R, N>(&text, &file)
}

/// [`read_baseline`] with each effect's window (`None`: on all the time),
/// as `--baseline` takes them back.
pub fn read_baseline_timed<R: Robot<N>, const N: usize>(
    path: &Path,
) -> Result<Vec<(Effect, Option<Window>)>, TuneError> {
    let (file, text) = read(path)?;
    timed_baseline_from_str::<R, N>(&text, &file)
}

/// The warning for a command that uses `robot`'s model alone (no measured
/// data to undo the rest on: `eval`, `simulate`, `synth`, Python's
/// `simulate`): what the baseline keeps apart from the model (the sensors'
/// effects, the motor sides, effects limited to a window) is left out
/// there. `None` when the model holds the whole baseline.
///
/// ```
/// use dynamics_cli::tune::left_out;
/// use dynamics_sim2real::effects::{Calibrated, Effect};
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let scale = Effect::EffortScale { joint: 0, scale: 1.2 };
/// let r = Calibrated::new(Pendulum::default(), vec![scale, Effect::coulomb(0, 0.1)]).unwrap();
/// let warning = left_out(&r, "simulate").unwrap();
/// assert!(warning.contains("effort_scale") && !warning.contains("coulomb"));
/// let folded = Calibrated::new(Pendulum::default(), vec![Effect::coulomb(0, 0.1)]).unwrap();
/// assert_eq!(left_out(&folded, "simulate"), None);
/// ```
pub fn left_out<R: Robot<N>, const N: usize>(
    robot: &Calibrated<R, N>,
    command: &str,
) -> Option<String> {
    let apart: Vec<&str> = robot
        .sensor_effects()
        .iter()
        .chain(robot.motor_effects())
        .chain(robot.windowed_effects().iter().map(|(e, _)| e))
        .map(|e| e.kind().name())
        .collect();
    (!apart.is_empty()).then(|| {
        format!(
            "--baseline: {} not part of the model `{command}` uses (undone on measured data by `diagnose` only): left out",
            apart.join(", ")
        )
    })
}

fn read(path: &Path) -> Result<(String, String), TuneError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| TuneError::Read {
        file: file.clone(),
        source,
    })?;
    Ok((file, text))
}

/// [`read_baseline`] on the JSON text `text` of a baseline document;
/// `file` names it in errors.
///
/// ```
/// use dynamics_cli::tune::baseline_from_str;
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let text = r#"{"effects": [{"kind": "viscous_friction", "joint": "j",
///     "parameters": [{"name": "fv", "value": 0.3}]}]}"#;
/// let effects = baseline_from_str::<Pendulum, 1>(text, "mine.json").unwrap();
/// assert_eq!(effects.len(), 1);
/// let err = baseline_from_str::<Pendulum, 1>("{}", "mine.json").unwrap_err();
/// assert!(err.to_string().starts_with("--baseline mine.json: top level:"));
/// ```
pub fn baseline_from_str<R: Robot<N>, const N: usize>(
    text: &str,
    file: &str,
) -> Result<Vec<Effect>, TuneError> {
    timed_baseline_from_str::<R, N>(text, file)?
        .into_iter()
        .enumerate()
        .map(|(i, (e, w))| match w {
            None => Ok(e),
            Some(_) => Err(TuneError::Shape {
                file: file.to_string(),
                place: format!("effect {i} ({})", e.kind()),
                problem: "an effect limited in time (`window`) is on all the time here: remove the entry, or its window".into(),
            }),
        })
        .collect()
}

/// [`baseline_from_str`] with each effect's window (`None`: on all the
/// time).
///
/// ```
/// use dynamics_cli::tune::timed_baseline_from_str;
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let text = r#"{"effects": [{"kind": "effort_offset", "joint": "j",
///     "parameters": [{"name": "offset", "value": 0.3}], "window": {"start": 1.0, "end": 2.5}}]}"#;
/// let effects = timed_baseline_from_str::<Pendulum, 1>(text, "mine.json").unwrap();
/// assert_eq!(effects[0].1.map(|w| (w.start, w.end)), Some((1.0, 2.5)));
/// ```
pub fn timed_baseline_from_str<R: Robot<N>, const N: usize>(
    text: &str,
    file: &str,
) -> Result<Vec<(Effect, Option<Window>)>, TuneError> {
    let file = file.to_string();
    let doc: Value = serde_json::from_str(text).map_err(|source| TuneError::Json {
        file: file.clone(),
        source,
    })?;
    entries(&doc, &file)?
        .into_iter()
        .map(|(place, entry)| {
            baseline::timed::<R, N>(&entry).map_err(|source| TuneError::Effect {
                file: file.clone(),
                place,
                source: Box::new(source),
            })
        })
        .collect()
}

/// What the calibration behind the baseline file `path` could tell of
/// each joint's friction: its report's `which.friction[]` spreads
/// (`coulomb_std`, `viscous_std`), by joint name in `R`'s order. `None`
/// for a baseline that is not a report with spreads (a list of
/// `effects`): every friction correction is then a change.
pub fn read_calibration<R: Robot<N>, const N: usize>(
    path: &Path,
) -> Result<Option<CalibrationSpread>, TuneError> {
    let (file, text) = read(path)?;
    calibration_from_str::<R, N>(&text, &file)
}

/// [`read_calibration`] on the JSON text `text`; `file` names it in
/// errors.
///
/// ```
/// use dynamics_cli::tune::calibration_from_str;
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [1.0, 0.0, 0.0]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let text = r#"{"which": {"effects": [], "friction": [{"joint": "j",
///     "coulomb_nominal": 0.0, "coulomb": 0.3, "viscous_nominal": 0.1, "viscous": 0.1,
///     "coulomb_std": 0.01, "viscous_std": 0.002}]}}"#;
/// let spread = calibration_from_str::<Pendulum, 1>(text, "cal.json").unwrap().unwrap();
/// assert_eq!((spread.coulomb[0], spread.viscous[0]), (0.01, 0.002));
/// assert_eq!((spread.coulomb_corrected[0], spread.viscous_corrected[0]), (true, false));
/// assert_eq!(calibration_from_str::<Pendulum, 1>(r#"{"effects": []}"#, "b.json").unwrap(), None);
/// let bad = r#"{"which": {"friction": [{"joint": "elbow", "viscous_std": 0.1}]}}"#;
/// let err = calibration_from_str::<Pendulum, 1>(bad, "cal.json").unwrap_err();
/// assert!(err.to_string().contains("which.friction[0]"), "{err}");
/// ```
pub fn calibration_from_str<R: Robot<N>, const N: usize>(
    text: &str,
    file: &str,
) -> Result<Option<CalibrationSpread>, TuneError> {
    let doc: Value = serde_json::from_str(text).map_err(|source| TuneError::Json {
        file: file.to_string(),
        source,
    })?;
    let Some(rows) = doc.pointer("/which/friction").and_then(Value::as_array) else {
        return Ok(None);
    };
    let shape = |place: String, problem: String| TuneError::Shape {
        file: file.to_string(),
        place,
        problem,
    };
    let mut spread = CalibrationSpread {
        coulomb: vec![f64::NAN; N],
        viscous: vec![f64::NAN; N],
        coulomb_corrected: vec![true; N],
        viscous_corrected: vec![true; N],
    };
    let mut any = false;
    for (i, row) in rows.iter().enumerate() {
        let place = format!("which.friction[{i}]");
        let joint = row.get("joint").and_then(Value::as_str).unwrap_or("");
        let Some(j) = R::JOINT_NAMES.iter().position(|n| *n == joint) else {
            return Err(shape(
                place,
                format!(
                    "joint {joint:?} is not one of the robot's joints ({})",
                    R::JOINT_NAMES.join(", ")
                ),
            ));
        };
        // Corrected: the calibrated level differs from the nominal one.
        let differs = |a: &str, b: &str| match (
            row.get(a).and_then(Value::as_f64),
            row.get(b).and_then(Value::as_f64),
        ) {
            (Some(x), Some(y)) => x != y,
            _ => true,
        };
        spread.coulomb_corrected[j] = differs("coulomb", "coulomb_nominal");
        spread.viscous_corrected[j] = differs("viscous", "viscous_nominal");
        for (name, into) in [
            ("coulomb_std", &mut spread.coulomb),
            ("viscous_std", &mut spread.viscous),
        ] {
            match row.get(name) {
                None | Some(Value::Null) => {}
                Some(v) => match v.as_f64().filter(|x| x.is_finite() && *x >= 0.0) {
                    Some(x) => {
                        into[j] = x;
                        any = true;
                    }
                    None => {
                        return Err(shape(
                            place,
                            format!("`{name}` must be a finite number >= 0, got {v}"),
                        ))
                    }
                },
            }
        }
    }
    Ok(any.then_some(spread))
}

/// The entries of a baseline document, each with its place in it.
fn entries(doc: &Value, file: &str) -> Result<Vec<(String, Entry)>, TuneError> {
    let shape = |place: &str, problem: &str| TuneError::Shape {
        file: file.to_string(),
        place: place.to_string(),
        problem: problem.to_string(),
    };
    let list = |arr: &Vec<Value>, at: &str| -> Result<Vec<(String, Entry)>, TuneError> {
        arr.iter()
            .enumerate()
            .map(|(i, v)| {
                let place = format!("{at}[{i}]");
                Ok((place.clone(), entry(v).map_err(|p| shape(&place, &p))?))
            })
            .collect()
    };
    if let Some(arr) = doc.pointer("/which/effects").and_then(Value::as_array) {
        return list(arr, "which.effects");
    }
    if let Some(arr) = doc.get("effects").and_then(Value::as_array) {
        return list(arr, "effects");
    }
    let verdict = doc.pointer("/which/verdict").ok_or_else(|| {
        shape(
            "top level",
            "expected `which.effects` (a diagnosis report), `which.verdict` or `effects`",
        )
    })?;
    let kind = verdict
        .get("kind")
        .and_then(Value::as_str)
        .ok_or_else(|| shape("which.verdict.kind", "missing, or not a string"))?;
    if kind == "none" || kind == "unexplained" {
        return Ok(Vec::new());
    }
    let place = |v: &Value| (v.get("joint").cloned(), v.get("point").cloned());
    let ranked = doc
        .pointer("/which/ranked")
        .and_then(Value::as_array)
        .ok_or_else(|| shape("which.ranked", "missing, or not an array"))?;
    let (i, top) = ranked
        .iter()
        .enumerate()
        .find(|(_, r)| {
            r.get("kind").and_then(Value::as_str) == Some(kind) && place(r) == place(verdict)
        })
        .ok_or_else(|| {
            shape(
                "which.ranked",
                &format!("no entry for the verdict's `{kind}`"),
            )
        })?;
    let at = format!("which.ranked[{i}]");
    Ok(vec![(at.clone(), entry(top).map_err(|p| shape(&at, &p))?)])
}

/// One entry: `kind`, `joint` (or none), `channel` (a delay's; or none),
/// `parameters[]` of `name`, `value`.
fn entry(v: &Value) -> Result<Entry, String> {
    let kind = v
        .get("kind")
        .and_then(Value::as_str)
        .ok_or("`kind` missing, or not a string")?
        .to_string();
    let joint = match v.get("joint") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(s.clone()),
        Some(_) => return Err("`joint` is not a string".into()),
    };
    let channel = match v.get("channel") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(s.parse().map_err(|e| format!("`channel`: {e}"))?),
        Some(_) => return Err("`channel` is not a string".into()),
    };
    let params = match v.get("parameters") {
        None | Some(Value::Null) => Vec::new(),
        Some(Value::Array(a)) => a.clone(),
        Some(_) => return Err("`parameters` is not an array".into()),
    };
    let parameters = params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let name = p
                .get("name")
                .and_then(Value::as_str)
                .ok_or(format!("parameters[{i}].name missing, or not a string"))?;
            let value = p.get("value").and_then(Value::as_f64).ok_or_else(|| {
                match p.get("note").and_then(Value::as_str) {
                    Some(note) => format!("parameters[{i}] ({name}) has no value: {note}"),
                    None => format!("parameters[{i}].value missing, or not a number"),
                }
            })?;
            Ok(Parameter {
                name: name.to_string(),
                value,
                std: p.get("std").and_then(Value::as_f64).unwrap_or(f64::NAN),
                note: None,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    let window = match v.get("window") {
        None | Some(Value::Null) => None,
        Some(w) => {
            let bound = |name: &str| -> Result<f64, String> {
                match w.get(name) {
                    // An open end: on to the end of the record.
                    None | Some(Value::Null) if name == "end" => Ok(f64::INFINITY),
                    Some(b) => b
                        .as_f64()
                        .ok_or_else(|| format!("`window.{name}` is not a number")),
                    None => Err(format!("`window.{name}` missing")),
                }
            };
            Some(Window {
                start: bound("start")?,
                end: bound("end")?,
            })
        }
    };
    let point = match v.get("point") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(s.clone()),
        Some(_) => return Err("`point` is not a string".into()),
    };
    Ok(Entry {
        kind,
        joint,
        point,
        channel,
        parameters,
        window,
    })
}
