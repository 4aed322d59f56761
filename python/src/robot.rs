//! The Python class `dynamics.Robot`: one robot's dynamics with NumPy in
//! and out, its parameters and limits, and the gap diagnosis.

use std::borrow::Cow;

use dynamics_cli::gap::{Motion, Recording, SynthRequest};
use dynamics_runtime::DynamicsError;
use numpy::{PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::arrays::{self, Arg};
use crate::kernel::{Kernel, Limits, Quantity};

/// A robot: its dynamics at one state `(N,)` or a batch `(B, N)` of states.
#[pyclass(name = "Robot", module = "dynamics")]
pub struct PyRobot {
    pub(crate) name: String,
    pub(crate) kernel: Box<dyn Kernel>,
    pub(crate) limits: Limits,
    pub(crate) motion: Motion,
}

impl PyRobot {
    /// A robot from its kernel, its limits and its home motion for `synth`.
    pub fn new(name: &str, kernel: Box<dyn Kernel>, limits: Limits, motion: Motion) -> Self {
        PyRobot {
            name: name.to_string(),
            kernel,
            limits,
            motion,
        }
    }

    fn nq_(&self) -> usize {
        self.kernel.joint_names().len()
    }

    /// Evaluates `what` on the arguments into new arrays, or into `out`
    /// (see [`arrays::out_buffers`]); returns its outputs (an array each;
    /// a float for a scalar of one state).
    fn compute<'py>(
        &self,
        py: Python<'py>,
        what: Quantity,
        objs: &[&Bound<'py, PyAny>],
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let names = what.inputs();
        let args = names
            .iter()
            .zip(objs)
            .map(|(name, obj)| Arg::new(name, obj))
            .collect::<PyResult<Vec<_>>>()?;
        let batch = arrays::check(&args, self.nq_())?;
        let shapes = self.kernel.out_shapes(what);
        let full: Vec<Vec<usize>> = shapes
            .iter()
            .map(|s| {
                let mut shape = Vec::with_capacity(s.len() + 1);
                shape.extend(batch.batch);
                shape.extend(s);
                shape
            })
            .collect();
        // Names for messages; borrowed for new arrays (no allocation on the
        // call path of a single state).
        let outs: Vec<(Cow<'static, str>, Bound<'py, PyArrayDyn<f64>>)> = match out {
            Some(out) => arrays::out_buffers(out, &full)?
                .into_iter()
                .map(|(name, a)| (Cow::Owned(name), a))
                .collect(),
            None => full
                .iter()
                .map(|shape| (Cow::Borrowed("result"), arrays::output(py, shape)))
                .collect(),
        };
        {
            let mut guards = outs
                .iter()
                .map(|(name, o)| o.try_readwrite().map_err(|e| arrays::write_error(name, e)))
                .collect::<PyResult<Vec<_>>>()?;
            let mut slices: Vec<&mut [f64]> = guards
                .iter_mut()
                .map(|g| g.as_slice_mut())
                .collect::<Result<_, _>>()
                .map_err(|e| PyValueError::new_err(e.to_string()))?;
            let inputs = batch.slices();
            let (n, kernel) = (batch.len(), &self.kernel);
            // A batch runs without the GIL; one state keeps it (releasing
            // and taking it back would cost about what the state costs).
            let result = if batch.batch.is_some() {
                py.detach(|| kernel.eval(what, n, &inputs, &mut slices))
            } else {
                kernel.eval(what, n, &inputs, &mut slices)
            };
            result.map_err(|e| match batch.batch {
                Some(_) => PyValueError::new_err(e.to_string()),
                None => PyValueError::new_err(e.source.to_string()),
            })?;
        }
        outs.into_iter()
            .zip(&shapes)
            .map(|((_, o), s)| -> PyResult<Bound<'py, PyAny>> {
                if s.is_empty() && batch.batch.is_none() {
                    let x = o
                        .readonly()
                        .as_slice()
                        .map(|s| s[0])
                        .map_err(|e| PyValueError::new_err(e.to_string()))?;
                    Ok(x.into_pyobject(py)?.into_any())
                } else {
                    Ok(o.into_any())
                }
            })
            .collect::<PyResult<_>>()
    }

    fn one<'py>(
        &self,
        py: Python<'py>,
        what: Quantity,
        objs: &[&Bound<'py, PyAny>],
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let mut v = self.compute(py, what, objs, out)?;
        v.pop().ok_or_else(|| PyValueError::new_err("no result"))
    }

    fn tuple<'py>(
        &self,
        py: Python<'py>,
        what: Quantity,
        objs: &[&Bound<'py, PyAny>],
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.compute(py, what, objs, out)?)
    }
}

fn vec_array<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArrayDyn<f64>> {
    let a = arrays::output(py, &[v.len()]);
    if let Ok(mut w) = a.try_readwrite() {
        if let Ok(s) = w.as_slice_mut() {
            s.copy_from_slice(v);
        }
    }
    a
}

#[pymethods]
impl PyRobot {
    /// `Robot(name)`: the robot called `name` (see `robots()`); a user's
    /// package makes its own robot without a name.
    #[new]
    #[pyo3(signature = (name=None))]
    fn py_new(name: Option<&str>) -> PyResult<Self> {
        crate::robot_by_name(name)
    }

    /// The robot's name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Joint names in coordinate order.
    #[getter]
    fn joint_names(&self) -> Vec<&'static str> {
        self.kernel.joint_names()
    }

    /// Number of joint coordinates N.
    #[getter]
    fn nq(&self) -> usize {
        self.nq_()
    }

    /// The run-time parameters, name -> value (a copy; change one with `set`).
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (i, name) in self.kernel.param_names().iter().enumerate() {
            if let Some(v) = self.kernel.param(i) {
                d.set_item(name, v)?;
            }
        }
        Ok(d)
    }

    /// Sets run-time parameter `name` to `value`.
    ///
    /// Raises KeyError (listing the known names) for an unknown name and
    /// ValueError for a value that is not finite.
    fn set(&mut self, name: &str, value: f64) -> PyResult<()> {
        let names = self.kernel.param_names();
        if !names.contains(&name) {
            return Err(PyKeyError::new_err(format!(
                "unknown parameter `{name}`; {} has: {}",
                self.name,
                if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(", ")
                }
            )));
        }
        if !value.is_finite() {
            return Err(PyValueError::new_err(format!(
                "{name} = {value}: a parameter must be finite"
            )));
        }
        self.kernel
            .set_param(name, value)
            .map_err(|e: DynamicsError| PyValueError::new_err(e.to_string()))
    }

    /// Lower position limits (-inf where none).
    #[getter]
    fn lower<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        vec_array(py, &self.limits.lower)
    }

    /// Upper position limits (+inf where none).
    #[getter]
    fn upper<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        vec_array(py, &self.limits.upper)
    }

    /// Velocity limits (+inf where none).
    #[getter]
    fn velocity_limit<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        vec_array(py, &self.limits.velocity)
    }

    /// Effort limits (+inf where none).
    #[getter]
    fn effort_limit<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        vec_array(py, &self.limits.effort)
    }

    /// Links of the inertial regressor, in its column order.
    #[getter]
    fn link_names(&self) -> Vec<&'static str> {
        self.kernel.link_names()
    }

    /// Frames `frame_pose` knows.
    #[getter]
    fn frame_names(&self) -> Vec<&'static str> {
        self.kernel.frame_names()
    }

    /// Inertial parameters of every link of `link_names`, `(10 L,)`:
    /// `regressor(q, v, a) @ inertial_parameters()` is the rigid-body part of `rnea`.
    fn inertial_parameters<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        vec_array(py, &self.kernel.inertial_parameters())
    }

    /// Inverse dynamics: the efforts `tau` that give accelerations `a`.
    ///
    /// `out`: a C-contiguous float64 array of the result's shape, written in
    /// place and returned (ValueError naming it when it does not fit).
    #[pyo3(signature = (q, v, a, *, out=None))]
    fn rnea<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::Rnea, &[q, v, a], out)
    }

    /// The inertia matrix `M(q)`, `(N, N)` or `(B, N, N)`.
    ///
    /// `out`: a C-contiguous float64 array of the result's shape, written in
    /// place and returned (ValueError naming it when it does not fit).
    #[pyo3(signature = (q, *, out=None))]
    fn mass_matrix<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::MassMatrix, &[q], out)
    }

    /// Gravity efforts `g(q)` (what holds the robot still).
    ///
    /// `out`: a C-contiguous float64 array of the result's shape, written in
    /// place and returned (ValueError naming it when it does not fit).
    #[pyo3(signature = (q, *, out=None))]
    fn gravity<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::Gravity, &[q], out)
    }

    /// Efforts at zero acceleration, `C(q, v) v + g(q)` plus damping and friction.
    ///
    /// `out`: a C-contiguous float64 array of the result's shape, written in
    /// place and returned (ValueError naming it when it does not fit).
    #[pyo3(signature = (q, v, *, out=None))]
    fn nle<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::Nle, &[q, v], out)
    }

    /// The Christoffel Coriolis matrix `C(q, v)`.
    ///
    /// `out`: a C-contiguous float64 array of the result's shape, written in
    /// place and returned (ValueError naming it when it does not fit).
    #[pyo3(signature = (q, v, *, out=None))]
    fn coriolis_matrix<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::CoriolisMatrix, &[q, v], out)
    }

    /// Forward dynamics: the accelerations under efforts `tau`.
    ///
    /// `out`: a C-contiguous float64 array of the result's shape, written in
    /// place and returned (ValueError naming it when it does not fit).
    #[pyo3(signature = (q, v, tau, *, out=None))]
    fn aba<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::Aba, &[q, v, tau], out)
    }

    /// `(dtau_dq, dtau_dv)` of the inverse dynamics.
    ///
    /// `out`: a tuple of C-contiguous float64 arrays of the results' shapes,
    /// written in place and returned (ValueError naming one that does not fit).
    #[pyo3(signature = (q, v, a, *, out=None))]
    fn rnea_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        self.tuple(py, Quantity::RneaDerivatives, &[q, v, a], out)
    }

    /// `(ddq_dq, ddq_dv, ddq_dtau)` of the forward dynamics (`ddq_dtau = M^-1`).
    ///
    /// `out`: a tuple of C-contiguous float64 arrays of the results' shapes,
    /// written in place and returned (ValueError naming one that does not fit).
    #[pyo3(signature = (q, v, tau, *, out=None))]
    fn aba_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        self.tuple(py, Quantity::AbaDerivatives, &[q, v, tau], out)
    }

    /// The inertial regressor `Y(q, v, a)`, `(N, 10 L)`.
    ///
    /// `out`: a C-contiguous float64 array of the result's shape, written in
    /// place and returned (ValueError naming it when it does not fit).
    #[pyo3(signature = (q, v, a, *, out=None))]
    fn regressor<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        a: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::Regressor, &[q, v, a], out)
    }

    /// The linearised model `(A, B)` of `x' = f(x, u)`, `x = [q; v]`, `u = tau`,
    /// about `(q, v, tau)`: continuous (`dt=None`), `A_c = [[0, I], [ddq_dq,
    /// ddq_dv]]` `(2N, 2N)` and `B_c = [[0], [M^-1]]` `(2N, N)`, as the runtime's
    /// `linearize::state_space`; with `dt` (s) the runtime's zero-order hold
    /// (`StateSpace::discretize`): `A_d = exp(A_c dt)`, `B_d = int_0^dt exp(A_c s) ds B_c`.
    ///
    /// `out`: a tuple of two C-contiguous float64 arrays, written in place.
    #[pyo3(signature = (q, v, tau, dt=None, *, out=None))]
    fn state_space<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
        dt: Option<f64>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let what = match dt {
            None => Quantity::StateSpace,
            Some(h) if h.is_finite() && h > 0.0 => Quantity::StateSpaceDiscrete(h),
            Some(h) => {
                return Err(PyValueError::new_err(format!(
                    "dt = {h}: the step must be a finite positive number of seconds"
                )))
            }
        };
        self.tuple(py, what, &[q, v, tau], out)
    }

    /// Kinetic energy `T(q, v)`: a float, or `(B,)`.
    fn kinetic_energy<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::KineticEnergy, &[q, v], None)
    }

    /// Potential energy (gravity and springs) `Pi(q)`: a float, or `(B,)`.
    fn potential_energy<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.one(py, Quantity::PotentialEnergy, &[q], None)
    }

    /// World pose (4 x 4 homogeneous) of frame `frame` (see `frame_names`).
    fn frame_pose<'py>(
        &self,
        py: Python<'py>,
        frame: &str,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let names = self.kernel.frame_names();
        let index = names.iter().position(|n| *n == frame).ok_or_else(|| {
            PyKeyError::new_err(format!(
                "unknown frame `{frame}`; {} has: {}",
                self.name,
                names.join(", ")
            ))
        })?;
        self.one(py, Quantity::FramePose(index), &[q], None)
    }

    /// Synthetic measured data with a withheld effect, as `dynamics synth` writes it:
    /// `{"train": csv_text, "holdout": csv_text, "truth": dict}`.
    #[pyo3(signature = (effect=None, joint=None, magnitude=None, seed=1, excitation="sines",
        duration=8.0, noise_q=2e-5, noise_qd=2e-3, noise_tau=2e-3))]
    #[allow(clippy::too_many_arguments)]
    fn synth<'py>(
        &self,
        py: Python<'py>,
        effect: Option<&str>,
        joint: Option<String>,
        magnitude: Option<f64>,
        seed: u64,
        excitation: &str,
        duration: f64,
        noise_q: f64,
        noise_qd: f64,
        noise_tau: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let bad = |e: String| PyValueError::new_err(e);
        let req = SynthRequest {
            robot: self.name.clone(),
            kind: effect
                .map(str::parse)
                .transpose()
                .map_err(|e| bad(format!("effect: {e}")))?,
            joint,
            magnitude,
            seed,
            excitation: excitation
                .parse()
                .map_err(|e| bad(format!("excitation: {e}")))?,
            duration,
            noise: dynamics_sim2real::synth::Noise {
                q: noise_q,
                qd: noise_qd,
                tau_relative: noise_tau,
            },
        };
        let (kernel, motion) = (&self.kernel, &self.motion);
        let out = py
            .detach(|| kernel.synth(motion, &req, &Recording::default()))
            .map_err(|e| bad(e.to_string()))?;
        let d = PyDict::new(py);
        d.set_item("train", out.train)?;
        d.set_item("holdout", out.holdout)?;
        let truth = serde_json::to_string(&out.truth).map_err(|e| bad(e.to_string()))?;
        d.set_item("truth", py.import("json")?.call_method1("loads", (truth,))?)?;
        Ok(d)
    }

    /// The robot under a computed-torque controller on its own model following
    /// a reference, as `dynamics simulate` (the same function and options):
    /// `{"t": (T,), "q", "qd", "qdd", "tau", "reference": (T, N)}`.
    ///
    /// `motion`: "sines" (default), "chirp", "pick-place" or the path of a CSV
    /// with columns `t, q_<joint>`. `duration` (s), `rate` (Hz), `seed`,
    /// `bandwidth` (rad/s), `home` and `amplitude` (one value or one per
    /// joint) as the flags. `effects` act on the simulated robot only,
    /// `baseline` on it and on the controller's model: each a JSON file's path
    /// or the document as a mapping (a diagnosis report dict works).
    #[pyo3(signature = (motion=None, *, duration=8.0, rate=1000.0, seed=1, bandwidth=12.0,
        home=None, amplitude=None, effects=None, baseline=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        motion: Option<&Bound<'py, PyAny>>,
        duration: f64,
        rate: f64,
        seed: u64,
        bandwidth: f64,
        home: Option<&Bound<'py, PyAny>>,
        amplitude: Option<&Bound<'py, PyAny>>,
        effects: Option<&Bound<'py, PyAny>>,
        baseline: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        crate::tasks::simulate(
            self,
            py,
            crate::tasks::SimulateRequest {
                motion,
                duration,
                rate,
                seed,
                bandwidth,
                home,
                amplitude,
                effects,
                baseline,
            },
        )
    }

    /// Least-squares identification of friction, offsets, rotor inertias and
    /// link parameters on `train`, judged on `holdout`: the JSON of
    /// `dynamics identify --json` as a dict. Data as for `diagnose` (paths,
    /// DataFrames, mappings of arrays); `topic`: a ROS 2 bag's JointState
    /// topic (default /joint_states). Data warnings go to the `dynamics` logger.
    #[pyo3(signature = (train, holdout, *, topic=None))]
    fn identify<'py>(
        &self,
        py: Python<'py>,
        train: &Bound<'py, PyAny>,
        holdout: &Bound<'py, PyAny>,
        topic: Option<String>,
    ) -> PyResult<Bound<'py, PyAny>> {
        crate::tasks::identify(self, py, train, holdout, topic)
    }

    /// The gap diagnosis (see `dynamics.Robot.diagnose` in the stubs).
    #[pyo3(signature = (train, holdout, *, columns=None, topic=None, train_window=None,
        holdout_window=None, noise_tau=None, noise_q=None, noise_qd=None, hold_links=false,
        judge_links=false, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn diagnose<'py>(
        &self,
        py: Python<'py>,
        train: &Bound<'py, PyAny>,
        holdout: &Bound<'py, PyAny>,
        columns: Option<&str>,
        topic: Option<String>,
        train_window: Option<&Bound<'py, PyAny>>,
        holdout_window: Option<&Bound<'py, PyAny>>,
        noise_tau: Option<&Bound<'py, PyAny>>,
        noise_q: Option<&Bound<'py, PyAny>>,
        noise_qd: Option<&Bound<'py, PyAny>>,
        hold_links: bool,
        judge_links: bool,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        crate::diagnose::run(
            self,
            py,
            crate::diagnose::Request {
                train,
                holdout,
                columns,
                topic,
                train_window,
                holdout_window,
                noise: [noise_tau, noise_q, noise_qd],
                hold_links,
                judge_links,
                progress,
            },
        )
    }

    /// A copy with its own parameters.
    fn copy(&self) -> Self {
        PyRobot {
            name: self.name.clone(),
            kernel: self.kernel.boxed_clone(),
            limits: self.limits.clone(),
            motion: self.motion.clone(),
        }
    }

    fn __repr__(&self) -> String {
        format!("Robot({:?}, nq={})", self.name, self.nq_())
    }
}
