//! `Robot.diagnose(train, holdout, **options)`: the command line's
//! diagnosis on files (every layout `dynamics diagnose` reads) or on data in
//! memory (a mapping of arrays, a pandas DataFrame), returning the JSON
//! report as a dict.
//!
//! Data in memory become the CSV text of the file format, numbers written
//! with Rust's shortest round-trip formatting, and go through the same
//! reader as a file: the same checks, repairs and warnings, and the same
//! report as the command line on a file holding the same numbers.

use std::fmt::Write;
use std::sync::Mutex;

use dynamics_cli::gap::{parse_window, DataFile};
use dynamics_sim2real::diagnose::{Options, SensorNoise};
use numpy::PyUntypedArrayMethods;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

use crate::arrays::Arg;
use crate::kernel::Source;
use crate::robot::PyRobot;

/// The arguments of one call.
pub struct Request<'a, 'py> {
    pub train: &'a Bound<'py, PyAny>,
    pub holdout: &'a Bound<'py, PyAny>,
    pub columns: Option<&'a str>,
    /// The topic of a ROS 2 bag (`--topic`).
    pub topic: Option<String>,
    pub train_window: Option<&'a Bound<'py, PyAny>>,
    pub holdout_window: Option<&'a Bound<'py, PyAny>>,
    /// `noise_tau`, `noise_q`, `noise_qd`.
    pub noise: [Option<&'a Bound<'py, PyAny>>; 3],
    /// `hold_links` (`--hold-links`).
    pub hold_links: bool,
    /// `judge_links` (`--judge-links`).
    pub judge_links: bool,
    pub progress: Option<Bound<'py, PyAny>>,
}

/// Where the diagnosis reports its progress (`progress=`): nowhere
/// (`None`, `False`), a callable `progress(done, total)` (`done` never
/// decreasing), a tqdm bar
/// (`True`, when tqdm is installed: `tqdm.auto`, so a notebook gets its
/// widget) or, `True` without tqdm, the logger `dynamics` at INFO every
/// tenth of the candidates. Never raw writes to the terminal.
enum Progress {
    Silent,
    /// The callable and what it was last told.
    Callable(Py<PyAny>, Told),
    Bar(Py<PyAny>),
    /// The logger and the last tenth logged.
    Log(Py<PyAny>, Told),
}

impl Progress {
    fn new(py: Python<'_>, obj: Option<Bound<'_, PyAny>>) -> PyResult<Self> {
        let Some(obj) = obj else {
            return Ok(Progress::Silent);
        };
        if obj.is_instance_of::<pyo3::types::PyBool>() {
            if !obj.extract::<bool>()? {
                return Ok(Progress::Silent);
            }
            return Ok(match py.import("tqdm.auto") {
                Ok(tqdm) => {
                    let kwargs = pyo3::types::PyDict::new(py);
                    kwargs.set_item("desc", "diagnose: fitting candidates")?;
                    kwargs.set_item("unit", "fit")?;
                    kwargs.set_item("leave", false)?;
                    Progress::Bar(tqdm.getattr("tqdm")?.call((), Some(&kwargs))?.unbind())
                }
                Err(_) => {
                    let logger = py
                        .import("logging")?
                        .call_method1("getLogger", ("dynamics",))?;
                    Progress::Log(logger.unbind(), Told::default())
                }
            });
        }
        if !obj.is_callable() {
            return Err(PyTypeError::new_err(
                "progress: give True (a tqdm bar, or log lines without tqdm), \
                 or a callable progress(done, total)",
            ));
        }
        Ok(Progress::Callable(obj.unbind(), Told::default()))
    }

    /// `done` of `total` candidates fitted (called from worker threads).
    fn update(&self, done: usize, total: usize) {
        if let Progress::Silent = self {
            return;
        }
        Python::attach(|py| {
            let result = match self {
                Progress::Silent => Ok(()),
                Progress::Callable(cb, told) => {
                    if told.advance(done, total) {
                        cb.call1(py, (done, total)).map(drop)
                    } else {
                        Ok(())
                    }
                }
                Progress::Bar(bar) => (|| -> PyResult<()> {
                    let bar = bar.bind(py);
                    match bar.getattr("total")?.extract::<Option<usize>>()? {
                        Some(t) if t == total => {}
                        // Another stage: the bar starts over.
                        Some(_) => {
                            bar.call_method1("reset", (total,))?;
                        }
                        None => bar.setattr("total", total)?,
                    }
                    let n: usize = bar.getattr("n")?.extract()?;
                    bar.call_method1("update", (done.saturating_sub(n),))?;
                    Ok(())
                })(),
                Progress::Log(logger, told) => {
                    let tenth = (10 * done).checked_div(total).unwrap_or(10);
                    if tenth > 0 && told.advance(tenth, total) {
                        logger
                            .call_method1(
                                py,
                                "info",
                                (format!("diagnose: {done} of {total} candidates fitted"),),
                            )
                            .map(drop)
                    } else {
                        Ok(())
                    }
                }
            };
            if let Err(e) = result {
                e.write_unraisable(py, None);
            }
        });
    }

    /// Closes a bar.
    fn close(&self, py: Python<'_>) {
        if let Progress::Bar(bar) = self {
            if let Err(e) = bar.call_method0(py, "close") {
                e.write_unraisable(py, None);
            }
        }
    }
}

/// What a progress sink was last told, `(total, count)`: worker threads
/// report as they finish, not in order; under the GIL (so one at a time) a
/// count not above the last one of the same total is dropped, so the sink
/// sees counts that never decrease and ends on `(total, total)`. A new total
/// (another stage) starts over.
#[derive(Default)]
struct Told(Mutex<(usize, usize)>);

impl Told {
    /// Whether `count` of `total` is news (and remembers it).
    fn advance(&self, count: usize, total: usize) -> bool {
        let mut last = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if last.0 != total {
            *last = (total, 0);
        }
        if count > 0 && count <= last.1 {
            return false;
        }
        last.1 = count;
        true
    }
}

/// A window as `"A:B"` or `(A, B)`, checked as the command line checks it.
pub(crate) fn window(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<(f64, f64)>> {
    let Some(obj) = obj else { return Ok(None) };
    let text = match obj.extract::<String>() {
        Ok(s) => s,
        Err(_) => {
            let (a, b): (f64, f64) = obj.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "{what}: give \"START:END\" or (START, END) in seconds"
                ))
            })?;
            format!("{a}:{b}")
        }
    };
    parse_window(&text)
        .map(Some)
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))
}

/// One value or one per joint.
pub(crate) fn levels(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Vec<f64>>> {
    let Some(obj) = obj else { return Ok(None) };
    if let Ok(x) = obj.extract::<f64>() {
        return Ok(Some(vec![x]));
    }
    obj.extract::<Vec<f64>>()
        .map(Some)
        .map_err(|_| PyTypeError::new_err(format!("{what}: give a number or one number per joint")))
}

/// CSV text of the file format from a mapping `{"t", "q", ["qd"], "tau"}`.
fn csv_of_mapping(obj: &Bound<'_, PyAny>, joints: &[&str], what: &str) -> PyResult<String> {
    let get = |key: &str| -> PyResult<Option<Bound<'_, PyAny>>> {
        match obj.get_item(key) {
            Ok(v) => Ok(Some(v)),
            Err(e) if e.is_instance_of::<pyo3::exceptions::PyKeyError>(obj.py()) => Ok(None),
            Err(e) => Err(e),
        }
    };
    let need = |key: &'static str| -> PyResult<Bound<'_, PyAny>> {
        get(key)?.ok_or_else(|| {
            PyValueError::new_err(format!(
                "{what}: the mapping has no `{key}` (give t (T,), q (T, N), tau (T, N), and qd (T, N) if measured)"
            ))
        })
    };
    let (t, q, tau) = (need("t")?, need("q")?, need("tau")?);
    let qd = get("qd")?;
    let n = joints.len();
    let t = Arg::new("t", &t)?;
    let mut cols: Vec<(&str, Arg)> = vec![("q", Arg::new("q", &q)?)];
    if let Some(qd) = &qd {
        cols.push(("qd", Arg::new("qd", qd)?));
    }
    cols.push(("tau", Arg::new("tau", &tau)?));
    let rows = match t.array().shape() {
        [r] => *r,
        s => {
            return Err(PyValueError::new_err(format!(
                "{what}: t has shape {s:?}, expected (T,)"
            )))
        }
    };
    for (name, a) in &cols {
        let s = a.array().shape();
        if s != [rows, n] {
            return Err(PyValueError::new_err(format!(
                "{what}: {name} has shape {s:?}, expected ({rows}, {n}) (T samples of this robot's {n} joints)"
            )));
        }
    }
    let mut text = String::from("t");
    for (name, _) in &cols {
        for j in joints {
            let _ = write!(text, ",{name}_{j}");
        }
    }
    text.push('\n');
    let t = t.array().as_array();
    let views: Vec<_> = cols.iter().map(|(_, a)| a.array().as_array()).collect();
    for k in 0..rows {
        // Non-finite numbers are written as they are: the reader names
        // the row and column.
        let _ = write!(text, "{}", t[[k]]);
        for v in &views {
            for j in 0..n {
                let _ = write!(text, ",{}", v[[k, j]]);
            }
        }
        text.push('\n');
    }
    Ok(text)
}

/// Where `obj` (a path, a DataFrame or a mapping of arrays) has its data.
pub(crate) fn source(
    obj: &Bound<'_, PyAny>,
    what: &str,
    columns: Option<&str>,
    topic: Option<&str>,
    window: Option<(f64, f64)>,
    joints: &[&str],
) -> PyResult<Source> {
    let py = obj.py();
    let os = py.import("os")?;
    let is_path = obj.is_instance_of::<pyo3::types::PyString>()
        || obj.is_instance(&os.getattr("PathLike")?)?;
    if is_path {
        let path: String = os.call_method1("fspath", (obj,))?.extract()?;
        let columns = columns
            .map(str::parse)
            .transpose()
            .map_err(|e| PyValueError::new_err(format!("columns: {e}")))?;
        return Ok(Source::File(Box::new(DataFile {
            path: path.into(),
            columns,
            window,
            topic: topic.map(str::to_string),
        })));
    }
    if let Some(topic) = topic {
        return Err(PyValueError::new_err(format!(
            "{what}: topic {topic} reads a ROS 2 bag; data in memory have no topics"
        )));
    }
    if columns.is_some() {
        return Err(PyValueError::new_err(format!(
            "{what}: `columns` maps the columns of a file; data in memory need the names \
             t, q_<joint>, qd_<joint>, tau_<joint> (DataFrame) or keys t, q, qd, tau (mapping)"
        )));
    }
    let text = if obj.hasattr("to_csv")? && obj.hasattr("columns")? {
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("index", false)?;
        obj.call_method("to_csv", (), Some(&kwargs))?.extract()?
    } else if obj.hasattr("keys")? {
        csv_of_mapping(obj, joints, what)?
    } else {
        return Err(PyTypeError::new_err(format!(
            "{what}: give a path, a pandas DataFrame with the CSV's columns, or a mapping \
             {{\"t\": (T,), \"q\": (T, N), \"qd\": (T, N), \"tau\": (T, N)}}"
        )));
    };
    Ok(Source::Csv {
        text,
        name: what.to_string(),
        window,
    })
}

/// Runs the diagnosis and returns the report as a dict; the warnings go
/// to the logger `dynamics` as well (they are in the report's `warnings`).
pub fn run<'py>(
    robot: &PyRobot,
    py: Python<'py>,
    req: Request<'_, 'py>,
) -> PyResult<Bound<'py, PyAny>> {
    let joints = robot.kernel.joint_names();
    let train = source(
        req.train,
        "train",
        req.columns,
        req.topic.as_deref(),
        window(req.train_window, "train_window")?,
        &joints,
    )?;
    let holdout = source(
        req.holdout,
        "holdout",
        req.columns,
        req.topic.as_deref(),
        window(req.holdout_window, "holdout_window")?,
        &joints,
    )?;
    let [tau, q, qd] = [
        levels(req.noise[0], "noise_tau")?,
        levels(req.noise[1], "noise_q")?,
        levels(req.noise[2], "noise_qd")?,
    ];
    if tau.is_none() && (q.is_some() || qd.is_some()) {
        return Err(PyValueError::new_err(
            "noise_q and noise_qd need noise_tau (the stated noise replaces the estimated one)",
        ));
    }
    let options = Options {
        noise: tau.map(|tau| SensorNoise {
            q: q.unwrap_or_else(|| vec![0.0]),
            qd: qd.unwrap_or_else(|| vec![0.0]),
            tau,
        }),
        hold_links: req.hold_links,
        judge_links: req.judge_links,
        ..Options::default()
    };
    let reporter = Progress::new(py, req.progress)?;
    let progress = |done: usize, total: usize| reporter.update(done, total);
    let kernel = &robot.kernel;
    let result = py.detach(|| kernel.diagnose(&train, &holdout, &options, &progress));
    reporter.close(py);
    let (report, warnings) = result.map_err(|e| PyValueError::new_err(e.to_string()))?;
    let logger = py
        .import("logging")?
        .call_method1("getLogger", ("dynamics",))?;
    for w in warnings {
        logger.call_method1("warning", (w,))?;
    }
    let json = serde_json::to_string(&report).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (json,))
}
