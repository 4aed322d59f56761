//! One robot behind an object-safe trait ([`Kernel`]), so that a single
//! Python class serves every robot: each call takes a whole batch of
//! states as flat row-major slices and loops over it in code monomorphised
//! for the robot (the dynamic dispatch is once a call, not once a state),
//! on rayon's threads above [`PARALLEL_FROM`] states.

use std::path::PathBuf;

use dynamics_cli::gap::{self, DataFile, GapError, Motion, SynthOutput, SynthRequest};
use dynamics_cli::identify::to_json as identify_json;
use dynamics_cli::simulate::{simulation, SimulateArgs};
use dynamics_cli::tune::baseline_from_str;
use dynamics_cli::RobotInfo;
use dynamics_runtime::linearize::{self, BlockMatrix, DiscretizeError};
use dynamics_runtime::{DynamicsError, Parameters, Robot};
use dynamics_sim2real::data::{read_csv_str, Measured};
use dynamics_sim2real::diagnose::{diagnose_owned, Options, Report};
use dynamics_sim2real::effects::Calibrated;
use dynamics_sim2real::identify::{identify, Options as IdentifyOptions};
use nalgebra::{SMatrix, SVector};
use rayon::prelude::*;

/// Below this many states a batch runs on the calling thread: rayon's
/// hand-off costs a few microseconds, about what 10 states of the Panda's
/// inverse dynamics cost.
pub const PARALLEL_FROM: usize = 64;

/// States a rayon task handles (enough to amortise the task, few enough
/// to balance two to a few dozen cores).
const CHUNK: usize = 32;

/// What a batch call computes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quantity {
    /// Inverse dynamics `tau(q, v, a)`.
    Rnea,
    /// Inertia matrix `M(q)`.
    MassMatrix,
    /// Gravity efforts `g(q)`.
    Gravity,
    /// Efforts at zero acceleration `nle(q, v)`.
    Nle,
    /// Christoffel Coriolis matrix `C(q, v)`.
    CoriolisMatrix,
    /// Forward dynamics `ddq(q, v, tau)`.
    Aba,
    /// `(dtau_dq, dtau_dv)` at `(q, v, a)`.
    RneaDerivatives,
    /// `(ddq_dq, ddq_dv, ddq_dtau)` at `(q, v, tau)`.
    AbaDerivatives,
    /// The inertial regressor `Y(q, v, a)`, `N x 10 L`.
    Regressor,
    /// `T(q, v)`.
    KineticEnergy,
    /// `Pi(q)`.
    PotentialEnergy,
    /// World pose of a frame (its index), 4 x 4.
    FramePose(usize),
    /// The continuous state-space model `(A_c, B_c)` at `(q, v, tau)`.
    StateSpace,
    /// Its zero-order-hold discretisation `(A_d, B_d)` for a step (s).
    StateSpaceDiscrete(f64),
}

impl Quantity {
    /// The names of the inputs, in order.
    pub fn inputs(self) -> &'static [&'static str] {
        match self {
            Quantity::Rnea | Quantity::RneaDerivatives | Quantity::Regressor => &["q", "v", "a"],
            Quantity::MassMatrix
            | Quantity::Gravity
            | Quantity::PotentialEnergy
            | Quantity::FramePose(_) => &["q"],
            Quantity::Nle | Quantity::CoriolisMatrix | Quantity::KineticEnergy => &["q", "v"],
            Quantity::Aba
            | Quantity::AbaDerivatives
            | Quantity::StateSpace
            | Quantity::StateSpaceDiscrete(_) => &["q", "v", "tau"],
        }
    }
}

/// Why one state of a call failed.
#[derive(Debug, thiserror::Error)]
pub enum StateError {
    /// The dynamics failed (a mass matrix not positive definite, ...).
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// The state-space model could not be discretised.
    #[error(transparent)]
    Discretize(#[from] DiscretizeError),
}

/// A batch call that failed at one state.
#[derive(Debug, thiserror::Error)]
#[error("state {state}: {source}")]
pub struct BatchError {
    /// Index of the state in the batch.
    pub state: usize,
    /// The cause.
    pub source: StateError,
}

/// Where data for the diagnosis come from.
#[derive(Debug, Clone)]
pub enum Source {
    /// A file as the command line reads it.
    File(Box<DataFile>),
    /// CSV text in the file format (from arrays or a DataFrame); `name`
    /// names it in errors and warnings.
    Csv {
        /// The text.
        text: String,
        /// Its name in messages.
        name: String,
        /// Seconds from the first sample, start inclusive, end exclusive.
        window: Option<(f64, f64)>,
    },
}

impl Source {
    fn read<const N: usize>(&self, joints: &[&str; N]) -> Result<Measured<N>, GapError> {
        Ok(self.read_described(joints)?.0)
    }

    /// The data, and for a bag what was read (file, topic, messages, time range).
    fn read_described<const N: usize>(
        &self,
        joints: &[&str; N],
    ) -> Result<(Measured<N>, Option<String>), GapError> {
        match self {
            Source::File(f) => f.read_described(joints),
            Source::Csv { text, name, window } => {
                let m = read_csv_str(text, joints, name)?;
                Ok((
                    match window {
                        Some((a, b)) => m.window(*a, *b),
                        None => m,
                    },
                    None,
                ))
            }
        }
    }

    /// Where it is, for messages.
    pub fn describe(&self) -> String {
        match self {
            Source::File(f) => f.path.display().to_string(),
            Source::Csv { name, .. } => name.clone(),
        }
    }

    /// A CSV file read whole.
    pub fn path(path: impl Into<PathBuf>) -> Self {
        Source::File(Box::new(DataFile::csv(path)))
    }
}

/// A baseline document (`--baseline`, `--effects`): its JSON text and its
/// name in errors (the file, or what the Python argument was).
#[derive(Debug, Clone)]
pub struct EffectsDoc {
    /// The JSON text.
    pub text: String,
    /// Its name in messages.
    pub name: String,
}

/// What `simulate` gives, as flat row-major arrays of `T` samples.
#[derive(Debug, Clone, Default)]
pub struct SimulationArrays {
    /// Times, `T`.
    pub t: Vec<f64>,
    /// Positions, `T x N`.
    pub q: Vec<f64>,
    /// Velocities, `T x N`.
    pub qd: Vec<f64>,
    /// Accelerations, `T x N`.
    pub qdd: Vec<f64>,
    /// Efforts, `T x N`.
    pub tau: Vec<f64>,
    /// Reference positions, `T x N`.
    pub reference: Vec<f64>,
    /// Warnings as the command line prints them (what of the baseline the
    /// model leaves out).
    pub warnings: Vec<String>,
}

/// What `identify` gives: the JSON of `identify --json`, the data's
/// warnings as the command line prints them, and what was read of bags.
#[derive(Debug, Clone)]
pub struct IdentifyOutput {
    /// The result (`dynamics_cli::identify::to_json`).
    pub json: serde_json::Value,
    /// Warnings about the data, one line each.
    pub warnings: Vec<String>,
    /// For each bag read: file, topic, messages, time range.
    pub about: Vec<String>,
}

/// Joint limits (URDF `<limit>`; infinite where none).
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// Lower position limits.
    pub lower: Vec<f64>,
    /// Upper position limits.
    pub upper: Vec<f64>,
    /// Velocity limits.
    pub velocity: Vec<f64>,
    /// Effort limits.
    pub effort: Vec<f64>,
}

impl Limits {
    /// No limits on `n` joints.
    pub fn none(n: usize) -> Self {
        Limits {
            lower: vec![f64::NEG_INFINITY; n],
            upper: vec![f64::INFINITY; n],
            velocity: vec![f64::INFINITY; n],
            effort: vec![f64::INFINITY; n],
        }
    }

    /// The four constants a URDF robot's `robot!` emits.
    pub fn of<const N: usize>(
        lower: [f64; N],
        upper: [f64; N],
        velocity: [f64; N],
        effort: [f64; N],
    ) -> Self {
        Limits {
            lower: lower.to_vec(),
            upper: upper.to_vec(),
            velocity: velocity.to_vec(),
            effort: effort.to_vec(),
        }
    }
}

/// A robot whatever its type: what the Python class calls.
pub trait Kernel: Send + Sync {
    /// Joint names in coordinate order.
    fn joint_names(&self) -> Vec<&'static str>;
    /// Run-time parameter names.
    fn param_names(&self) -> Vec<&'static str>;
    /// Parameter `index`'s value.
    fn param(&self, index: usize) -> Option<f64>;
    /// Sets a parameter by name.
    fn set_param(&mut self, name: &str, value: f64) -> Result<(), DynamicsError>;
    /// Links of the inertial regressor, in its order.
    fn link_names(&self) -> Vec<&'static str>;
    /// Frames [`Quantity::FramePose`] knows.
    fn frame_names(&self) -> Vec<&'static str>;
    /// Inertial parameters `pi_l` of every link, `10 L` values.
    fn inertial_parameters(&self) -> Vec<f64>;
    /// The shape of each output of `what` for one state.
    fn out_shapes(&self, what: Quantity) -> Vec<Vec<usize>>;
    /// Evaluates `what` at `inputs.len()` inputs of `batch` states each
    /// (row-major `batch x N`), writing each output (row-major, the states
    /// one after the other).
    fn eval(
        &self,
        what: Quantity,
        batch: usize,
        inputs: &[&[f64]],
        outs: &mut [&mut [f64]],
    ) -> Result<(), BatchError>;
    /// The gap diagnosis of `train` against `holdout`, with the warnings as
    /// the command line prints them.
    fn diagnose(
        &self,
        train: &Source,
        holdout: &Source,
        options: &Options,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<(Report, Vec<String>), GapError>;
    /// Synthetic training and held-out data with a withheld effect.
    fn synth(
        &self,
        motion: &Motion,
        req: &SynthRequest,
        rec: &gap::Recording,
    ) -> Result<SynthOutput, GapError>;
    /// `dynamics simulate`: the robot plus `baseline` as the controller's
    /// model, and plus `effects` as the plant, following `args.motion`.
    fn simulate(
        &self,
        info: &RobotInfo,
        args: &SimulateArgs,
        baseline: Option<&EffectsDoc>,
        effects: Option<&EffectsDoc>,
    ) -> Result<SimulationArrays, String>;
    /// `dynamics identify` on `train` against `holdout`.
    fn identify(&self, train: &Source, holdout: &Source) -> Result<IdentifyOutput, String>;
    /// A copy.
    fn boxed_clone(&self) -> Box<dyn Kernel>;
}

/// [`Kernel`] for a robot type with `N` coordinates (made by [`kernel`]).
#[derive(Debug, Clone)]
pub struct Typed<R, const N: usize>(pub R);

/// `robot` behind the [`Kernel`] trait.
///
/// ```ignore
/// let k: Box<dyn Kernel> = _dynamics::kernel(robots::Panda::rigid());
/// ```
pub fn kernel<R, const N: usize>(robot: R) -> Box<dyn Kernel>
where
    R: Robot<N> + Clone + Send + Sync + 'static,
{
    Box::new(Typed::<R, N>(robot))
}

/// One state's part of every output of a batch call.
pub struct Out<'a, 'b> {
    parts: &'a mut [&'b mut [f64]],
    sizes: &'a [usize],
    k: usize,
}

impl Out<'_, '_> {
    /// The state's part of output `o`.
    fn get(&mut self, o: usize) -> &mut [f64] {
        let size = self.sizes[o];
        &mut self.parts[o][self.k * size..(self.k + 1) * size]
    }

    /// Writes a matrix row-major into output `o`.
    fn matrix<const R: usize, const C: usize>(&mut self, o: usize, m: &SMatrix<f64, R, C>) {
        let out = self.get(o);
        for i in 0..R {
            for j in 0..C {
                out[i * C + j] = m[(i, j)];
            }
        }
    }

    /// Writes a block matrix row-major into output `o`.
    fn blocks<const N: usize, const R: usize, const C: usize>(
        &mut self,
        o: usize,
        m: &BlockMatrix<N, R, C>,
    ) {
        let out = self.get(o);
        let cols = C * N;
        for i in 0..R * N {
            for j in 0..cols {
                out[i * cols + j] = m[(i, j)];
            }
        }
    }

    /// Writes a vector into output `o`.
    fn vector<const R: usize>(&mut self, o: usize, v: &SVector<f64, R>) {
        self.get(o).copy_from_slice(v.as_slice());
    }
}

/// Runs `f` on every state of a batch, each output cut into the states'
/// parts; over rayon's threads when the batch is large. `scratch` makes
/// what `f` may reuse from one state to the next (once a chunk).
fn run<const N: usize, S, F>(
    batch: usize,
    inputs: &[&[f64]],
    outs: &mut [&mut [f64]],
    scratch: impl Fn() -> S + Sync,
    f: F,
) -> Result<(), BatchError>
where
    F: Fn(&mut S, [SVector<f64, N>; 3], &mut Out) -> Result<(), StateError> + Sync,
{
    let sizes: Vec<usize> = outs.iter().map(|o| o.len() / batch.max(1)).collect();
    let load = |k: usize| -> [SVector<f64, N>; 3] {
        let mut x = [SVector::<f64, N>::zeros(); 3];
        for (slot, input) in x.iter_mut().zip(inputs) {
            *slot = SVector::<f64, N>::from_column_slice(&input[k * N..(k + 1) * N]);
        }
        x
    };
    // One chunk of `count` states from `start`, with its part of every output.
    let chunk = |start: usize, count: usize, parts: &mut [&mut [f64]]| -> Result<(), BatchError> {
        let mut s = scratch();
        for k in 0..count {
            let mut out = Out {
                parts: &mut *parts,
                sizes: &sizes,
                k,
            };
            f(&mut s, load(start + k), &mut out).map_err(|source| BatchError {
                state: start + k,
                source,
            })?;
        }
        Ok(())
    };
    if batch < PARALLEL_FROM {
        return chunk(0, batch, outs);
    }
    let mut chunks: Vec<(usize, Vec<&mut [f64]>)> = (0..batch.div_ceil(CHUNK))
        .map(|c| (c * CHUNK, Vec::with_capacity(outs.len())))
        .collect();
    for (o, &size) in outs.iter_mut().zip(&sizes) {
        for (c, part) in o.chunks_mut(CHUNK * size).enumerate() {
            chunks[c].1.push(part);
        }
    }
    chunks.into_par_iter().try_for_each(|(start, mut parts)| {
        let count = CHUNK.min(batch - start);
        chunk(start, count, &mut parts)
    })
}

impl<R, const N: usize> Kernel for Typed<R, N>
where
    R: Robot<N> + Clone + Send + Sync + 'static,
{
    fn joint_names(&self) -> Vec<&'static str> {
        R::JOINT_NAMES.to_vec()
    }

    fn param_names(&self) -> Vec<&'static str> {
        <R::Params as Parameters>::NAMES.to_vec()
    }

    fn param(&self, index: usize) -> Option<f64> {
        self.0.params().value(index)
    }

    fn set_param(&mut self, name: &str, value: f64) -> Result<(), DynamicsError> {
        self.0.params_mut().set(name, value)
    }

    fn link_names(&self) -> Vec<&'static str> {
        R::LINK_NAMES.to_vec()
    }

    fn frame_names(&self) -> Vec<&'static str> {
        R::FRAME_NAMES.to_vec()
    }

    fn inertial_parameters(&self) -> Vec<f64> {
        let mut pi = vec![SVector::<f64, 10>::zeros(); R::LINK_NAMES.len()];
        // The length is the one the robot asks for: this cannot fail.
        let _ = self.0.inertial_parameters(&mut pi);
        pi.iter().flat_map(|p| p.iter().copied()).collect()
    }

    fn out_shapes(&self, what: Quantity) -> Vec<Vec<usize>> {
        let l = R::LINK_NAMES.len();
        match what {
            Quantity::Rnea | Quantity::Gravity | Quantity::Nle | Quantity::Aba => vec![vec![N]],
            Quantity::MassMatrix | Quantity::CoriolisMatrix => vec![vec![N, N]],
            Quantity::RneaDerivatives => vec![vec![N, N]; 2],
            Quantity::AbaDerivatives => vec![vec![N, N]; 3],
            Quantity::Regressor => vec![vec![N, 10 * l]],
            Quantity::KineticEnergy | Quantity::PotentialEnergy => vec![vec![]],
            Quantity::FramePose(_) => vec![vec![4, 4]],
            Quantity::StateSpace | Quantity::StateSpaceDiscrete(_) => {
                vec![vec![2 * N, 2 * N], vec![2 * N, N]]
            }
        }
    }

    fn eval(
        &self,
        what: Quantity,
        batch: usize,
        inputs: &[&[f64]],
        outs: &mut [&mut [f64]],
    ) -> Result<(), BatchError> {
        let r = &self.0;
        let none = || ();
        match what {
            Quantity::Rnea => run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, a], o| {
                o.vector(0, &r.inverse_dynamics(&q, &v, &a));
                Ok(())
            }),
            Quantity::MassMatrix => run::<N, _, _>(batch, inputs, outs, none, |_, [q, ..], o| {
                o.matrix(0, &r.mass_matrix(&q));
                Ok(())
            }),
            Quantity::Gravity => run::<N, _, _>(batch, inputs, outs, none, |_, [q, ..], o| {
                o.vector(0, &r.gravity(&q));
                Ok(())
            }),
            Quantity::Nle => run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, _], o| {
                o.vector(0, &r.nonlinear_effects(&q, &v));
                Ok(())
            }),
            Quantity::CoriolisMatrix => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, _], o| {
                    o.matrix(0, &r.coriolis_matrix(&q, &v));
                    Ok(())
                })
            }
            Quantity::Aba => run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, tau], o| {
                o.vector(0, &r.forward_dynamics(&q, &v, &tau)?);
                Ok(())
            }),
            Quantity::RneaDerivatives => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, a], o| {
                    let pj = r.perturbation_jacobians(&q, &v, &a);
                    o.matrix(0, &pj.k);
                    o.matrix(1, &pj.d);
                    Ok(())
                })
            }
            Quantity::AbaDerivatives => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, tau], o| {
                    let ss = linearize::state_space(r, &q, &v, &tau)?;
                    o.matrix(0, &ss.a.blocks[1][0]);
                    o.matrix(1, &ss.a.blocks[1][1]);
                    o.matrix(2, &ss.b.blocks[1][0]);
                    Ok(())
                })
            }
            Quantity::Regressor => {
                let l = R::LINK_NAMES.len();
                let scratch = || vec![SMatrix::<f64, N, 10>::zeros(); l];
                run::<N, _, _>(batch, inputs, outs, scratch, |y, [q, v, a], o| {
                    r.inertial_regressor(&q, &v, &a, y)?;
                    let out = o.get(0);
                    for i in 0..N {
                        for (k, yl) in y.iter().enumerate() {
                            for c in 0..10 {
                                out[i * 10 * l + 10 * k + c] = yl[(i, c)];
                            }
                        }
                    }
                    Ok(())
                })
            }
            Quantity::KineticEnergy => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, _], o| {
                    o.get(0)[0] = r.kinetic_energy(&q, &v);
                    Ok(())
                })
            }
            Quantity::PotentialEnergy => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, ..], o| {
                    o.get(0)[0] = r.potential_energy(&q);
                    Ok(())
                })
            }
            Quantity::FramePose(index) => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, ..], o| {
                    // The index was checked against FRAME_NAMES by the caller.
                    if let Some(pose) = r.frame_pose(index, &q) {
                        o.matrix(0, &pose);
                    }
                    Ok(())
                })
            }
            Quantity::StateSpace => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, tau], o| {
                    let ss = linearize::state_space(r, &q, &v, &tau)?;
                    o.blocks(0, &ss.a);
                    o.blocks(1, &ss.b);
                    Ok(())
                })
            }
            Quantity::StateSpaceDiscrete(h) => {
                run::<N, _, _>(batch, inputs, outs, none, |_, [q, v, tau], o| {
                    let d = linearize::state_space(r, &q, &v, &tau)?.discretize(h)?;
                    o.blocks(0, &d.a);
                    o.blocks(1, &d.b);
                    Ok(())
                })
            }
        }
    }

    fn diagnose(
        &self,
        train: &Source,
        holdout: &Source,
        options: &Options,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<(Report, Vec<String>), GapError> {
        // What `dynamics_cli::gap::diagnose_data` does, with sources that
        // may be in memory (handed over to the diagnosis, not copied).
        let a = train.read(&R::JOINT_NAMES)?;
        let b = holdout.read(&R::JOINT_NAMES)?;
        let report = diagnose_owned(&self.0, a, b, options, progress)?;
        let warnings = dynamics_cli::warnings::lines(&report.warnings);
        Ok((report, warnings))
    }

    fn synth(
        &self,
        motion: &Motion,
        req: &SynthRequest,
        rec: &gap::Recording,
    ) -> Result<SynthOutput, GapError> {
        gap::synth_recorded(&self.0, motion, req, rec)
    }

    fn simulate(
        &self,
        info: &RobotInfo,
        args: &SimulateArgs,
        baseline: Option<&EffectsDoc>,
        effects: Option<&EffectsDoc>,
    ) -> Result<SimulationArrays, String> {
        // As `dynamics simulate`: the nominal model with the baseline folded
        // in, and the effects read for that model.
        let base = match baseline {
            Some(d) => baseline_from_str::<R, N>(&d.text, &d.name).map_err(|e| e.to_string())?,
            None => Vec::new(),
        };
        let model = Calibrated::new(self.0.clone(), base).map_err(|e| format!("baseline: {e}"))?;
        let warnings = dynamics_cli::tune::left_out(&model, "simulate")
            .into_iter()
            .collect();
        let effects = match effects {
            Some(d) => baseline_from_str::<Calibrated<R, N>, N>(&d.text, &d.name)
                .map_err(|e| e.to_string())?,
            None => Vec::new(),
        };
        let run = simulation(&model, info, args, effects).map_err(|e| e.to_string())?;
        let flat = |v: &[SVector<f64, N>]| -> Vec<f64> {
            v.iter().flat_map(|x| x.iter().copied()).collect()
        };
        let tr = &run.trajectory;
        Ok(SimulationArrays {
            t: tr.t.clone(),
            q: flat(&tr.q),
            qd: flat(&tr.qd),
            qdd: flat(&tr.qdd),
            tau: flat(&tr.tau),
            reference: flat(&run.reference),
            warnings,
        })
    }

    fn identify(&self, train: &Source, holdout: &Source) -> Result<IdentifyOutput, String> {
        // What `dynamics_cli::identify::identify_cmd` does, with sources
        // that may be in memory, on the same (uncalibrated) nominal model.
        let model = Calibrated::new(self.0.clone(), Vec::new()).map_err(|e| e.to_string())?;
        let (a, about_a) = train
            .read_described(&R::JOINT_NAMES)
            .map_err(|e| e.to_string())?;
        let (b, about_b) = holdout
            .read_described(&R::JOINT_NAMES)
            .map_err(|e| e.to_string())?;
        let all: Vec<_> = a.warnings.iter().chain(&b.warnings).cloned().collect();
        let id =
            identify(&model, &a, &b, &IdentifyOptions::default()).map_err(|e| e.to_string())?;
        Ok(IdentifyOutput {
            json: identify_json(<Calibrated<R, N> as Robot<N>>::NAME, &id),
            warnings: dynamics_cli::warnings::lines(&all),
            about: about_a.into_iter().chain(about_b).collect(),
        })
    }

    fn boxed_clone(&self) -> Box<dyn Kernel> {
        Box::new(self.clone())
    }
}
