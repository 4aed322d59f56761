//! `excite`: design an exciting motion within the robot's limits and write
//! it as CSV (`t, q_<joint>, qd_<joint>, qdd_<joint>`) with its design as
//! JSON; the condition number of today's default excitation (`synth`'s
//! sines) over the same duration is printed beside the design's.

use std::path::PathBuf;

use clap::Args;
use nalgebra::SVector;

use crate::gap::Motion;
use crate::info::JointLimits;
use crate::Res;
use dynamics_runtime::control::Reference;
use dynamics_runtime::Robot;
use dynamics_sim2real::excite::{self, DesignReport, Figures, Limits, Options};
use dynamics_sim2real::synth::{Excitation, ExcitationKind, Rng};

/// `excite`.
#[derive(Args, Debug, Clone)]
pub struct ExciteArgs {
    /// Duration, s (a whole number of periods).
    #[arg(long)]
    pub duration: f64,
    /// Sample rate of the CSV, Hz.
    #[arg(long, default_value_t = 1000.0)]
    pub rate: f64,
    /// Where to write the motion (CSV: t, q_<joint>, qd_<joint>, qdd_<joint>).
    #[arg(long)]
    pub out: PathBuf,
    /// Write the design here (JSON: coefficients, criterion, limit check, predicted
    /// identifiability).
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Start and end pose, one value per joint; default: the middle of each joint's range.
    #[arg(long = "from", value_delimiter = ',', value_name = "Q[,..]")]
    pub from: Option<Vec<f64>>,
    /// Fraction by which every limit is tightened (positions: of the range's width).
    #[arg(long, default_value_t = 0.1)]
    pub margin: f64,
    /// Acceleration limit, one value or one per joint (rad/s^2 or m/s^2).
    #[arg(long, value_delimiter = ',', value_name = "A[,..]")]
    pub acc_limit: Option<Vec<f64>>,
    /// Harmonics per joint (at least 3).
    #[arg(long, default_value_t = 5)]
    pub harmonics: usize,
    /// Period, s; default: the duration over the whole number of periods nearest to 5 s.
    #[arg(long)]
    pub period: Option<f64>,
    /// Criterion: condition (the condition number) or d-optimal.
    #[arg(long, default_value = "condition")]
    pub criterion: String,
    /// Evaluations of the criterion the search may spend.
    #[arg(long, default_value_t = 2000)]
    pub evaluations: usize,
    /// Random seed of the search (and of the default sines compared with).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Effort noise for the predicted identifiability, standard deviation per sample (N m or
    /// N), one value or one per joint; default: 0.002 of each joint's peak effort.
    #[arg(long, value_delimiter = ',', value_name = "SIGMA[,..]")]
    pub noise_tau: Option<Vec<f64>>,
    /// The nominal model.
    #[command(flatten)]
    pub model: crate::tune::ModelArgs,
}

/// One value per joint from a list of one or `N` values.
fn per_joint<const N: usize>(v: &[f64], what: &str) -> Result<SVector<f64, N>, String> {
    match v.len() {
        1 => Ok(SVector::repeat(v[0])),
        n if n == N => Ok(SVector::from_column_slice(v)),
        n => Err(format!("{what}: {n} values for {N} joints")),
    }
}

/// The limits `excite` designs within: the robot's (a URDF's) where it has
/// them, else the box its default motion can reach (`home +- 2
/// amplitude`, velocity `pi * amplitude`; see [`Limits::around`]).
///
/// ```
/// use dynamics_cli::{excite::limits, gap::Motion, JointLimits};
/// let m = Motion { home: vec![0.1], amplitude: vec![0.5] };
/// let l = limits::<1>(None, &m);
/// assert!((l.upper[0] - 1.1).abs() < 1e-12);
/// let urdf = JointLimits::of([-1.0], [1.0], [2.0], [9.0]);
/// assert_eq!(limits::<1>(Some(&urdf), &m).upper[0], 1.0);
/// ```
pub fn limits<const N: usize>(given: Option<&JointLimits>, motion: &Motion) -> Limits<N> {
    let home = SVector::from_fn(|j, _| motion.home.get(j).copied().unwrap_or(0.0));
    let amp = SVector::from_fn(|j, _| motion.amplitude.get(j).copied().unwrap_or(0.4));
    let fallback = Limits::around(home, amp);
    let v = |x: &[f64], d: f64| SVector::from_fn(|j, _| x.get(j).copied().unwrap_or(d));
    match given {
        Some(l) => Limits {
            lower: v(&l.lower, f64::NEG_INFINITY),
            upper: v(&l.upper, f64::INFINITY),
            velocity: v(&l.velocity, f64::INFINITY),
            effort: v(&l.effort, f64::INFINITY),
            acceleration: None,
        }
        .or(&fallback),
        None => fallback,
    }
}

/// The states of today's default excitation (`synth --excitation sines`
/// with `seed`) over `duration`, sampled at `rate`.
///
/// ```
/// use dynamics_cli::{excite::default_states, gap::Motion};
/// let s = default_states::<2>(&Motion::default(), 4.0, 50.0, 1);
/// assert_eq!(s.len(), 201);
/// ```
pub fn default_states<const N: usize>(
    motion: &Motion,
    duration: f64,
    rate: f64,
    seed: u64,
) -> Vec<Reference<N>> {
    let home = SVector::from_fn(|j, _| motion.home.get(j).copied().unwrap_or(0.0));
    let amp = SVector::from_fn(|j, _| motion.amplitude.get(j).copied().unwrap_or(0.4));
    let e = Excitation::new(
        ExcitationKind::Sines,
        home,
        amp,
        duration,
        &mut Rng::new(seed),
    );
    let n = (duration * rate).round() as usize;
    (0..=n).map(|k| e.at(k as f64 / rate)).collect()
}

/// The CSV text of samples `(t, reference)`.
///
/// ```
/// use dynamics_runtime::control::Reference;
/// let r = Reference { q: [1.0].into(), qd: [0.5].into(), qdd: [0.0].into() };
/// let text = dynamics_cli::excite::csv(&["j"], &[(0.0, r)]);
/// assert_eq!(text, "t,q_j,qd_j,qdd_j\n0,1,0.5,0\n");
/// ```
pub fn csv<const N: usize>(joints: &[&str; N], samples: &[(f64, Reference<N>)]) -> String {
    let mut out = String::from("t");
    for p in ["q", "qd", "qdd"] {
        for j in joints {
            out.push_str(&format!(",{p}_{j}"));
        }
    }
    out.push('\n');
    for (t, r) in samples {
        out.push_str(&format!("{t}"));
        for v in r.q.iter().chain(r.qd.iter()).chain(r.qdd.iter()) {
            out.push_str(&format!(",{v}"));
        }
        out.push('\n');
    }
    out
}

/// `excite` on `robot` (the nominal model) with what the program knows
/// of it.
pub fn excite_cmd<R: Robot<N> + Sync, const N: usize>(
    robot: &R,
    info: &crate::RobotInfo,
    args: &ExciteArgs,
) -> Res {
    let mut lim = limits::<N>(info.limits.as_ref(), &info.motion);
    if let Some(a) = &args.acc_limit {
        lim.acceleration = Some(per_joint(a, "--acc-limit")?);
    }
    if !(args.rate.is_finite() && args.rate > 0.0) {
        return Err(format!("--rate {}: not a positive rate", args.rate).into());
    }
    let mut o = Options::new(args.duration);
    o.period = args.period;
    o.harmonics = args.harmonics;
    o.margin = args.margin;
    o.q0 = args
        .from
        .as_deref()
        .map(|q| per_joint(q, "--from"))
        .transpose()?;
    o.criterion = args.criterion.parse()?;
    o.evaluations = args.evaluations;
    o.seed = args.seed;
    let noise = args
        .noise_tau
        .as_deref()
        .map(|n| per_joint(n, "--noise-tau"))
        .transpose()?;
    eprintln!(
        "designing {} s for {} ({} harmonics, period {} s, {} evaluations)",
        args.duration,
        info.name,
        o.harmonics,
        o.period(),
        o.evaluations
    );
    let d = excite::design(robot, &lim, &o)?;
    let samples = d.samples(args.rate);
    std::fs::write(&args.out, csv(&R::JOINT_NAMES, &samples))
        .map_err(|e| format!("{}: {e}", args.out.display()))?;
    let report = DesignReport::of(robot, &d, args.rate, noise)?;
    // Today's default over the same duration, on the same columns.
    let rate = (200.0 / d.motion.period).max(50.0);
    let default = Figures::of(&d.columns.stack(
        robot,
        &default_states::<N>(&info.motion, args.duration, rate, args.seed),
    )?)?;
    println!(
        "condition number of the base regressor ({} base parameters, friction, rotor inertia and offsets included): designed {:.1}, default sines {:.1}",
        d.columns.kept.len(),
        d.figures.condition,
        default.condition
    );
    let c = &report.check;
    println!(
        "limits (margin {}): positions {}, velocities {}, efforts {}{}",
        args.margin,
        ok(c.position),
        ok(c.velocity),
        ok(c.effort),
        if d.limits.acceleration.is_some() {
            format!(", accelerations {}", ok(c.acceleration))
        } else {
            String::new()
        }
    );
    let worst = report
        .identifiability
        .parameters
        .iter()
        .filter_map(|p| p.relative_std.map(|r| (r, &p.name)))
        .fold(None::<(f64, &String)>, |m, x| match m {
            Some(m) if m.0 >= x.0 => Some(m),
            _ => Some(x),
        });
    if let Some((r, name)) = worst {
        println!(
            "predicted: the least certain inertial base parameter is {name} ({:.1} % relative standard deviation); {} columns stay unidentifiable alone",
            100.0 * r,
            report.identifiability.unidentifiable.len()
        );
    }
    println!("motion: {}", args.out.display());
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&report)?;
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("design: {}", path.display());
    }
    Ok(())
}

fn ok(b: bool) -> &'static str {
    if b {
        "within"
    } else {
        "EXCEEDED"
    }
}
