//! `simulate`: the robot (with effects from a JSON file, optionally) under
//! a computed-torque controller on the nominal model following a reference
//! (the data generator's excitations: sines, chirp, pick-and-place; or a
//! CSV of positions), written as the trajectory CSV (docs/cli.md) (`t, q_<j>,
//! qd_<j>, qdd_<j>, tau_<j>`) with SVG plots of the positions against the
//! reference, the tracking error and the efforts.

use std::path::{Path, PathBuf};

use clap::Args;
use dynamics_runtime::control::{ComputedTorque, Controller, Reference};
use dynamics_runtime::ode::Tolerances;
use dynamics_runtime::{Robot, Trajectory};
use dynamics_sim2real::effects::Plant;
use dynamics_sim2real::synth::{Excitation, ExcitationKind, Rng};
use nalgebra::SVector;

use crate::info::RobotInfo;
use crate::plot::{svg, Series};
use crate::tune::{BaselineArgs, ModelArgs};
use crate::Res;

/// `simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// Reference: sines, chirp, pick-place, or a CSV file with columns `t` and `q_<joint>`
    /// (linearly interpolated; velocities and accelerations by central differences).
    #[arg(long, default_value = "sines", value_name = "KIND|FILE.csv")]
    pub motion: String,
    /// Duration, s (a CSV reference: its own, at most).
    #[arg(long, default_value_t = 8.0)]
    pub duration: f64,
    /// Output sample rate, Hz.
    #[arg(long, default_value_t = 1000.0)]
    pub rate: f64,
    /// Random seed of the excitation.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Closed-loop bandwidth of the controller, rad/s (kp = w^2, kd = 2 w).
    #[arg(long, default_value_t = 12.0)]
    pub bandwidth: f64,
    /// Home pose, one value per joint (default: the robot's, or zero).
    #[arg(long, value_delimiter = ',', value_name = "Q[,..]")]
    pub home: Option<Vec<f64>>,
    /// Amplitude per joint, or one for all (default: the robot's, or 0.4).
    #[arg(long, value_delimiter = ',', value_name = "A[,..]")]
    pub amplitude: Option<Vec<f64>>,
    /// Effects acting on the simulated robot (not known to the controller), in the format of
    /// `--baseline`; any kind (elasticity, backlash and sensor effects too).
    #[arg(long, value_name = "FILE.json")]
    pub effects: Option<PathBuf>,
    /// Output folder (default `out/simulate-<robot>`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The nominal model (the controller's, and the plant's before `--effects`).
    #[command(flatten)]
    pub model: ModelArgs,
    /// A calibrated baseline added to the nominal model.
    #[command(flatten)]
    pub baseline: BaselineArgs,
}

impl Default for SimulateArgs {
    /// The command line's defaults: sines for 8 s at 1 kHz, seed 1,
    /// bandwidth 12 rad/s, the robot's home and amplitudes, no effects.
    ///
    /// ```
    /// let args = dynamics_cli::simulate::SimulateArgs::default();
    /// assert_eq!((args.motion.as_str(), args.duration, args.rate), ("sines", 8.0, 1000.0));
    /// ```
    fn default() -> Self {
        SimulateArgs {
            motion: "sines".into(),
            duration: 8.0,
            rate: 1000.0,
            seed: 1,
            bandwidth: 12.0,
            home: None,
            amplitude: None,
            effects: None,
            out: None,
            model: ModelArgs::default(),
            baseline: BaselineArgs::default(),
        }
    }
}

/// A reference the controller follows.
enum Motion<const N: usize> {
    Excitation(Excitation<N>),
    Csv(Vec<f64>, Vec<SVector<f64, N>>),
}

impl<const N: usize> Motion<N> {
    fn at(&self, t: f64) -> Reference<N> {
        match self {
            Motion::Excitation(e) => e.at(t),
            Motion::Csv(ts, qs) => {
                let q = |t: f64| interpolate(ts, qs, t);
                let h = 1e-3;
                Reference {
                    q: q(t),
                    qd: (q(t + h) - q(t - h)) / (2.0 * h),
                    qdd: (q(t + h) - q(t) * 2.0 + q(t - h)) / (h * h),
                }
            }
        }
    }
}

fn interpolate<const N: usize>(ts: &[f64], qs: &[SVector<f64, N>], t: f64) -> SVector<f64, N> {
    let k = ts.partition_point(|&x| x <= t);
    if k == 0 {
        return qs[0];
    }
    if k >= ts.len() {
        return qs[ts.len() - 1];
    }
    let (a, b) = (ts[k - 1], ts[k]);
    let s = if b > a { (t - a) / (b - a) } else { 0.0 };
    qs[k - 1] * (1.0 - s) + qs[k] * s
}

/// Reads `t` and `q_<joint>` from a CSV file.
fn read_positions<const N: usize>(
    path: &Path,
    joints: &[&str; N],
) -> Result<(Vec<f64>, Vec<SVector<f64, N>>), String> {
    let file = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{file}: {e}"))?;
    let mut lines = text.lines().enumerate();
    let header: Vec<&str> = lines
        .next()
        .map(|(_, l)| l.split(',').map(str::trim).collect())
        .ok_or(format!("{file}: empty"))?;
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .ok_or(format!("{file}: line 1: no column `{name}`"))
    };
    let t_col = col("t")?;
    let q_cols = joints
        .iter()
        .map(|j| col(&format!("q_{j}")))
        .collect::<Result<Vec<_>, _>>()?;
    let (mut ts, mut qs) = (Vec::new(), Vec::new());
    for (i, line) in lines.filter(|(_, l)| !l.trim().is_empty()) {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |c: usize, what: &str| -> Result<f64, String> {
            cells
                .get(c)
                .and_then(|v| v.parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .ok_or(format!(
                    "{file}: line {}: `{what}` is not a finite number",
                    i + 1
                ))
        };
        let t = num(t_col, "t")?;
        if ts.last().is_some_and(|&last| t <= last) {
            return Err(format!("{file}: line {}: time does not increase", i + 1));
        }
        ts.push(t);
        let mut q = SVector::<f64, N>::zeros();
        for (j, &c) in q_cols.iter().enumerate() {
            q[j] = num(c, &format!("q_{}", joints[j]))?;
        }
        qs.push(q);
    }
    if ts.len() < 2 {
        return Err(format!("{file}: needs at least two rows"));
    }
    Ok((ts, qs))
}

/// A simulated run: the robot's trajectory (sampled at the output rate) and
/// the reference positions it followed, one per sample.
#[derive(Debug, Clone)]
pub struct Simulation<const N: usize> {
    /// `t, q, qd, qdd, tau` per sample (what `simulate` writes as CSV).
    pub trajectory: Trajectory<N>,
    /// The reference positions at each sample.
    pub reference: Vec<SVector<f64, N>>,
    /// The simulated span, s (`--duration`, or a CSV reference's own span if shorter).
    pub duration: f64,
}

/// What `simulate` computes, without writing anything: `robot` (the
/// nominal model, baseline included) as the controller's model, and the
/// plant `robot` plus `effects` (what `--effects` reads), under the
/// computed-torque controller following `args.motion` (`args.effects`,
/// `args.out` and the model flags are not read here).
///
/// ```
/// use dynamics_cli::simulate::{simulation, SimulateArgs};
/// use dynamics_cli::RobotInfo;
/// dynamics_macros::robot! {
///     pub robot Pendulum; gravity = [0.0, -9.81, 0.0];
///     link base; link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let args = SimulateArgs { duration: 0.5, rate: 100.0, ..SimulateArgs::default() };
/// let run = simulation(&Pendulum::default(), &RobotInfo::default(), &args, Vec::new()).unwrap();
/// assert_eq!((run.trajectory.t.len(), run.reference.len()), (51, 51));
/// // Computed torque on the exact model tracks the reference closely.
/// assert!((run.trajectory.q[50][0] - run.reference[50][0]).abs() < 1e-3);
/// ```
pub fn simulation<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    info: &RobotInfo,
    args: &SimulateArgs,
    effects: Vec<dynamics_sim2real::effects::Effect>,
) -> Result<Simulation<N>, Box<dyn std::error::Error>> {
    if !(args.rate.is_finite()
        && args.rate > 0.0
        && args.bandwidth.is_finite()
        && args.bandwidth > 0.0)
    {
        return Err("--rate and --bandwidth must be positive".into());
    }
    let pick = |given: &Option<Vec<f64>>, own: &[f64], default: f64, what: &str| {
        let v = given.clone().unwrap_or_else(|| own.to_vec());
        if v.iter().any(|x| !x.is_finite()) {
            return Err(format!("--{what}: not finite numbers"));
        }
        match v.len() {
            0 => Ok(SVector::<f64, N>::repeat(default)),
            1 if given.is_some() => Ok(SVector::<f64, N>::repeat(v[0])),
            n if n == N => Ok(SVector::<f64, N>::from_column_slice(&v)),
            n => Err(format!("--{what}: {n} values; the robot has {N} joints")),
        }
    };
    let home = pick(&args.home, &info.motion.home, 0.0, "home")?;
    let amplitude = pick(&args.amplitude, &info.motion.amplitude, 0.4, "amplitude")?;
    let (motion, duration) = match args.motion.parse::<ExcitationKind>() {
        Ok(kind) => {
            if !(args.duration.is_finite() && args.duration > 0.0) {
                return Err("--duration must be positive".into());
            }
            let e = Excitation::new(
                kind,
                home,
                amplitude,
                args.duration,
                &mut Rng::new(args.seed),
            );
            (Motion::Excitation(e), args.duration)
        }
        Err(_) if args.motion.ends_with(".csv") => {
            let (ts, qs) = read_positions(Path::new(&args.motion), &R::JOINT_NAMES)?;
            let span = ts[ts.len() - 1] - ts[0];
            let shifted: Vec<f64> = ts.iter().map(|t| t - ts[0]).collect();
            (Motion::Csv(shifted, qs), args.duration.min(span))
        }
        Err(e) => {
            return Err(format!(
                "--motion `{}`: {e}, or a CSV file of positions",
                args.motion
            )
            .into())
        }
    };
    let plant = Plant::new(robot.clone(), effects)?;
    let w = args.bandwidth;
    let mut controller = ComputedTorque {
        model: robot,
        kp: SVector::repeat(w * w),
        kd: SVector::repeat(2.0 * w),
    };
    let dt = 1.0 / args.rate;
    let n = (duration * args.rate).round() as usize + 1;
    let r0 = motion.at(0.0);
    let mut sim = plant.start(r0.q, r0.qd);
    let tol = Tolerances {
        rtol: 1e-9,
        atol: 1e-11,
        ..Default::default()
    };
    let mut tr = Trajectory::<N>::default();
    let mut refs = Vec::with_capacity(n);
    for k in 0..n {
        let t = k as f64 * dt;
        let r = motion.at(t);
        let tau = controller.effort(&sim.state.q, &sim.state.qd, &r);
        let d = plant.derivative(&sim.state, &tau, &sim.contact)?;
        tr.t.push(t);
        tr.q.push(sim.state.q);
        tr.qd.push(sim.state.qd);
        tr.qdd.push(d.qd);
        tr.tau.push(tau);
        refs.push(r.q);
        if k + 1 < n {
            sim.advance(&plant, (k + 1) as f64 * dt, &tau, tol)
                .map_err(|e| format!("at t = {t:.3} s: {e}"))?;
        }
    }
    Ok(Simulation {
        trajectory: tr,
        reference: refs,
        duration,
    })
}

/// Runs `simulate` on `robot` (the nominal model, baseline included):
/// [`simulation`] with the effects of `--effects`, written to `--out`.
pub fn simulate<R: Robot<N> + Clone, const N: usize>(
    robot: &R,
    info: &RobotInfo,
    args: &SimulateArgs,
) -> Res {
    let effects = match &args.effects {
        Some(path) => crate::tune::read_baseline::<R, N>(path)?,
        None => Vec::new(),
    };
    let Simulation {
        trajectory: tr,
        reference: refs,
        duration,
    } = simulation(robot, info, args, effects)?;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(format!("simulate-{}", info.name)));
    write_outputs(&dir, &info.name, &R::JOINT_NAMES, &tr, &refs)?;
    let worst = (0..N)
        .map(|j| {
            tr.q.iter()
                .zip(&refs)
                .map(|(q, r)| (q[j] - r[j]).abs())
                .fold(0.0, f64::max)
        })
        .collect::<Vec<_>>();
    println!(
        "{}: {} samples over {duration} s into {}; largest tracking error per joint: {}",
        info.name,
        tr.t.len(),
        dir.display(),
        R::JOINT_NAMES
            .iter()
            .zip(&worst)
            .map(|(j, e)| format!("{j} {e:.2e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

/// The CSV and the plots: per joint position against reference, the
/// tracking errors, the efforts.
fn write_outputs<const N: usize>(
    dir: &Path,
    name: &str,
    joints: &[&str; N],
    tr: &Trajectory<N>,
    refs: &[SVector<f64, N>],
) -> Res {
    let io = |p: &Path, e: std::io::Error| format!("{}: {e}", p.display());
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut csv = Vec::new();
    tr.write_csv(&mut csv, joints)?;
    let path = dir.join(format!("{name}.csv"));
    std::fs::write(&path, csv).map_err(|e| io(&path, e))?;
    let series = |f: &dyn Fn(usize, usize) -> f64, j: usize| -> Vec<(f64, f64)> {
        (0..tr.t.len()).map(|k| (tr.t[k], f(k, j))).collect()
    };
    let mut files = Vec::new();
    for (j, joint) in joints.iter().enumerate() {
        let lines = [
            Series {
                name: "simulated",
                points: series(&|k, j| tr.q[k][j], j),
            },
            Series {
                name: "reference",
                points: series(&|k, j| refs[k][j], j),
            },
        ];
        files.push((
            format!("q-{joint}.svg"),
            svg(&format!("{name}: {joint}"), "t [s]", "q", &lines, false),
        ));
    }
    let errors: Vec<Series> = joints
        .iter()
        .enumerate()
        .map(|(j, joint)| Series {
            name: joint,
            points: series(&|k, j| tr.q[k][j] - refs[k][j], j),
        })
        .collect();
    files.push((
        "error.svg".into(),
        svg(
            &format!("{name}: tracking error"),
            "t [s]",
            "q - q_ref",
            &errors,
            false,
        ),
    ));
    let efforts: Vec<Series> = joints
        .iter()
        .enumerate()
        .map(|(j, joint)| Series {
            name: joint,
            points: series(&|k, j| tr.tau[k][j], j),
        })
        .collect();
    files.push((
        "tau.svg".into(),
        svg(&format!("{name}: efforts"), "t [s]", "tau", &efforts, false),
    ));
    for (file, text) in files {
        let path = dir.join(file);
        std::fs::write(&path, text).map_err(|e| io(&path, e))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::SimulateArgs;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: SimulateArgs,
    }

    #[test]
    fn default_is_the_command_lines() {
        let parsed = Cli::parse_from(["simulate"]).args;
        let own = SimulateArgs::default();
        assert_eq!(
            (
                &parsed.motion,
                parsed.duration,
                parsed.rate,
                parsed.seed,
                parsed.bandwidth
            ),
            (&own.motion, own.duration, own.rate, own.seed, own.bandwidth)
        );
        assert!(parsed.home.is_none() && parsed.amplitude.is_none() && parsed.effects.is_none());
    }
}
