//! `Robot.simulate(...)` and `Robot.identify(...)`: the command line's
//! `simulate` and `identify` (the same functions of `dynamics_cli`), with
//! NumPy arrays and dicts instead of files.

use dynamics_cli::simulate::SimulateArgs;
use dynamics_cli::RobotInfo;
use numpy::{PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays;
use crate::diagnose::{levels, source};
use crate::kernel::EffectsDoc;
use crate::robot::PyRobot;

/// The arguments of `simulate`.
pub struct SimulateRequest<'a, 'py> {
    /// `--motion`: an excitation's name or a CSV path (`None`: sines).
    pub motion: Option<&'a Bound<'py, PyAny>>,
    pub duration: f64,
    pub rate: f64,
    pub seed: u64,
    pub bandwidth: f64,
    pub home: Option<&'a Bound<'py, PyAny>>,
    pub amplitude: Option<&'a Bound<'py, PyAny>>,
    /// `--effects`: a path or a JSON-like object.
    pub effects: Option<&'a Bound<'py, PyAny>>,
    /// `--baseline`: a path or a JSON-like object.
    pub baseline: Option<&'a Bound<'py, PyAny>>,
}

/// `obj` as a path if it is a `str` or `os.PathLike`.
fn as_path(obj: &Bound<'_, PyAny>) -> PyResult<Option<String>> {
    let os = obj.py().import("os")?;
    if obj.is_instance_of::<pyo3::types::PyString>() || obj.is_instance(&os.getattr("PathLike")?)? {
        Ok(Some(os.call_method1("fspath", (obj,))?.extract()?))
    } else {
        Ok(None)
    }
}

/// A baseline document from a path (read as `--baseline FILE` reads it) or
/// a JSON-like object (a diagnosis report dict, `{"effects": [...]}`).
fn effects_doc(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<EffectsDoc>> {
    let Some(obj) = obj else { return Ok(None) };
    if let Some(path) = as_path(obj)? {
        let text = std::fs::read_to_string(&path)
            .map_err(|e| PyValueError::new_err(format!("{what}: {path}: {e}")))?;
        return Ok(Some(EffectsDoc { text, name: path }));
    }
    let text: String = obj
        .py()
        .import("json")?
        .call_method1("dumps", (obj,))
        .map_err(|e| {
            PyTypeError::new_err(format!(
                "{what}: give a path to a JSON file or a JSON-like mapping \
                 (a diagnosis report, {{\"effects\": [...]}}): {e}"
            ))
        })?
        .extract()?;
    Ok(Some(EffectsDoc {
        text,
        name: format!("({what} given as a mapping)"),
    }))
}

/// A `(T,)` or `(T, N)` float64 array of `values`.
fn array<'py>(py: Python<'py>, values: &[f64], shape: &[usize]) -> Bound<'py, PyArrayDyn<f64>> {
    let a = arrays::output(py, shape);
    if let Ok(mut w) = a.try_readwrite() {
        if let Ok(s) = w.as_slice_mut() {
            s.copy_from_slice(values);
        }
    }
    a
}

/// `simulate`: `{"t": (T,), "q", "qd", "qdd", "tau", "reference": (T, N)}`.
pub fn simulate<'py>(
    robot: &PyRobot,
    py: Python<'py>,
    req: SimulateRequest<'_, 'py>,
) -> PyResult<Bound<'py, PyDict>> {
    let motion = match req.motion.map(as_path).transpose()? {
        None => "sines".to_string(),
        Some(Some(m)) => m,
        Some(None) => {
            return Err(PyTypeError::new_err(
                "motion: give \"sines\", \"chirp\", \"pick-place\" or the path of a CSV file \
                 with columns t and q_<joint>",
            ))
        }
    };
    let args = SimulateArgs {
        motion,
        duration: req.duration,
        rate: req.rate,
        seed: req.seed,
        bandwidth: req.bandwidth,
        home: levels(req.home, "home")?,
        amplitude: levels(req.amplitude, "amplitude")?,
        ..SimulateArgs::default()
    };
    let baseline = effects_doc(req.baseline, "baseline")?;
    let effects = effects_doc(req.effects, "effects")?;
    let info = RobotInfo {
        name: robot.name.clone(),
        motion: robot.motion.clone(),
        ..RobotInfo::default()
    };
    let kernel = &robot.kernel;
    let run = py
        .detach(|| kernel.simulate(&info, &args, baseline.as_ref(), effects.as_ref()))
        .map_err(PyValueError::new_err)?;
    // As the command line warns on stderr.
    let logger = py
        .import("logging")?
        .call_method1("getLogger", ("dynamics",))?;
    for w in &run.warnings {
        logger.call_method1("warning", (w,))?;
    }
    let (t, n) = (run.t.len(), robot.kernel.joint_names().len());
    let d = PyDict::new(py);
    d.set_item("t", array(py, &run.t, &[t]))?;
    for (key, values) in [
        ("q", &run.q),
        ("qd", &run.qd),
        ("qdd", &run.qdd),
        ("tau", &run.tau),
        ("reference", &run.reference),
    ] {
        d.set_item(key, array(py, values, &[t, n]))?;
    }
    Ok(d)
}

/// `identify`: the JSON of `identify --json` as a dict; the data's warnings
/// to the logger `dynamics` (WARNING), what was read of bags to it (INFO).
pub fn identify<'py>(
    robot: &PyRobot,
    py: Python<'py>,
    train: &Bound<'py, PyAny>,
    holdout: &Bound<'py, PyAny>,
    topic: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let joints = robot.kernel.joint_names();
    let topic = topic.as_deref();
    let train = source(train, "train", None, topic, None, &joints)?;
    let holdout = source(holdout, "holdout", None, topic, None, &joints)?;
    let kernel = &robot.kernel;
    let out = py
        .detach(|| kernel.identify(&train, &holdout))
        .map_err(PyValueError::new_err)?;
    let logger = py
        .import("logging")?
        .call_method1("getLogger", ("dynamics",))?;
    for about in out.about {
        logger.call_method1("info", (format!("data: {about}"),))?;
    }
    for w in out.warnings {
        logger.call_method1("warning", (w,))?;
    }
    let json =
        serde_json::to_string(&out.json).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (json,))
}
