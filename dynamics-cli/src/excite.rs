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
    /// A diagnosis report (JSON): design a motion that tells its ambiguous pairs apart (the
    /// verdict and its rival, every effect and what it is ambiguous with) instead of one that
    /// conditions the whole identification.
    #[arg(long, value_name = "REPORT.json")]
    pub separate: Option<PathBuf>,
    /// Keep the link frames clear: every moving frame's origin above the ground (the plane
    /// through the base's origin normal to gravity) by --ground-clearance, every two origins the
    /// joints can bring together apart by --link-clearance. Only frame origins, not meshes.
    #[arg(long)]
    pub clearance: bool,
    /// Least height of a moving link frame's origin above the ground, m (with --clearance).
    #[arg(long, default_value_t = 0.05)]
    pub ground_clearance: f64,
    /// Least distance between the origins of two link frames the joints can bring together, m
    /// (with --clearance).
    #[arg(long, default_value_t = 0.05)]
    pub link_clearance: f64,
    /// Plot the motion here (SVG): positions, velocities and efforts (inverse dynamics of the
    /// nominal model) of every joint over time, each joint's limits (margin applied) shaded.
    #[arg(long, value_name = "PLOT.svg")]
    pub plot: Option<PathBuf>,
    /// The nominal model.
    #[command(flatten)]
    pub model: crate::tune::ModelArgs,
}

/// The plot of a designed motion: three panels (positions, velocities,
/// efforts from the inverse dynamics of `robot`), one line per joint over
/// time, each joint's limits of the design (margin applied) shaded behind;
/// at most 2000 points a line.
///
/// ```
/// use dynamics_sim2real::excite::{design, Limits, Options};
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let p = Pendulum::default();
/// let mut o = Options::new(4.0);
/// o.evaluations = 20;
/// let d = design(&p, &Limits::new([-1.0], [1.0], [3.0], [50.0]), &o).unwrap();
/// let svg = dynamics_cli::excite::plot(&p, &d);
/// assert_eq!(svg.matches("<polyline").count(), 3);
/// ```
pub fn plot<R: Robot<N>, const N: usize>(robot: &R, d: &excite::Design<N>) -> String {
    use crate::plot::{stack, svg_shaded, Series, Shade};
    let rate = (2000.0 / d.duration).min(1000.0);
    let samples = d.samples(rate);
    let effort: Vec<SVector<f64, N>> = samples
        .iter()
        .map(|(_, r)| robot.inverse_dynamics(&r.q, &r.qd, &r.qdd))
        .collect();
    let l = &d.limits;
    let names: Vec<String> = R::JOINT_NAMES.iter().map(|s| s.to_string()).collect();
    let labels: Vec<String> = names.iter().map(|n| format!("{n} limits")).collect();
    type Pick<'a, const N: usize> = &'a dyn Fn(usize, usize) -> f64;
    let q = |k: usize, j: usize| samples[k].1.q[j];
    let qd = |k: usize, j: usize| samples[k].1.qd[j];
    let tau = |k: usize, j: usize| effort[k][j];
    let panel = |title: &str, unit: &str, pick: Pick<N>, band: &dyn Fn(usize) -> (f64, f64)| {
        let series: Vec<Series> = (0..N)
            .map(|j| Series {
                name: &names[j],
                points: (0..samples.len())
                    .map(|k| (samples[k].0, pick(k, j)))
                    .collect(),
            })
            .collect();
        let shades: Vec<Shade> = (0..N)
            .map(|j| Shade {
                x: None,
                y: Some(band(j)),
                label: &labels[j],
            })
            .collect();
        svg_shaded(title, "t [s]", unit, &series, &shades, false)
    };
    stack(&[
        panel("positions", "q [rad or m]", &q, &|j| {
            (l.lower[j], l.upper[j])
        }),
        panel("velocities", "qd [rad/s or m/s]", &qd, &|j| {
            (-l.velocity[j], l.velocity[j])
        }),
        panel(
            "efforts (inverse dynamics)",
            "effort [N m or N]",
            &tau,
            &|j| (-l.effort[j], l.effort[j]),
        ),
    ])
}

/// A report entry's kind and place (joint, else point).
fn report_entry(v: &serde_json::Value) -> Option<(String, Option<String>)> {
    let kind = v.get("kind")?.as_str()?.to_string();
    let place = v
        .get("joint")
        .or_else(|| v.get("point"))
        .and_then(|p| p.as_str())
        .map(String::from);
    Some((kind, place))
}

/// The ambiguous pairs of a diagnosis report (`which.verdict` with its
/// `rival` when ambiguous; every `which.effects[]` with its
/// `ambiguous_with`), as `((kind, place), (kind, place))`.
///
/// ```
/// let report: serde_json::Value = serde_json::from_str(r#"{"which": {"verdict":
///   {"kind": "coulomb_friction", "joint": "j2", "status": "ambiguous",
///    "rival": {"kind": "effort_offset", "joint": "j2"}}, "effects": []}}"#).unwrap();
/// let pairs = dynamics_cli::excite::ambiguous_pairs(&report);
/// assert_eq!(pairs[0].1 .0, "effort_offset");
/// ```
#[allow(clippy::type_complexity)]
pub fn ambiguous_pairs(
    report: &serde_json::Value,
) -> Vec<((String, Option<String>), (String, Option<String>))> {
    let entry = report_entry;
    let mut out = Vec::new();
    let which = &report["which"];
    let verdict = &which["verdict"];
    if verdict["status"] == "ambiguous" {
        if let (Some(a), Some(b)) = (entry(verdict), entry(&verdict["rival"])) {
            out.push((a, b));
        }
    }
    for e in which["effects"].as_array().into_iter().flatten() {
        if let (Some(a), Some(b)) = (entry(e), entry(&e["ambiguous_with"])) {
            let seen = out
                .iter()
                .any(|(x, y)| (x == &a && y == &b) || (x == &b && y == &a));
            if !seen {
                out.push((a, b));
            }
        }
    }
    out
}

/// The rival pairs of a diagnosis report that `excite --separate`
/// separates (see [`ambiguous_pairs`]), with a label each (`kind place vs
/// kind place`); the error names a pair it cannot separate and why. A pair
/// the report marks `inseparable` (no motion separates it: one base
/// parameter) is left out; when every pair is, the error gives the
/// report's reason.
///
/// ```
/// use dynamics_cli::excite::rivals;
/// use dynamics_sim2real::excite::Rival;
/// dynamics_macros::robot! {
///     pub robot Pendulum;
///     gravity = [0.0, -9.81, 0.0];
///     link base;
///     link rod { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
///     joint j = revolute(base -> rod) { transfer = [rot_z(q)]; }
/// }
/// let report: serde_json::Value = serde_json::from_str(r#"{"which": {"verdict":
///   {"kind": "time_delay", "status": "ambiguous",
///    "rival": {"kind": "armature", "joint": "j"}}, "effects": []}}"#).unwrap();
/// let (pairs, labels) = rivals::<Pendulum, 1>(&report).unwrap();
/// assert_eq!(pairs, vec![(Rival::Delay, Rival::Armature(0))]);
/// assert_eq!(labels[0], "time_delay  vs armature j");
/// // A pair the report marks inseparable is left out.
/// let report: serde_json::Value = serde_json::from_str(r#"{"which": {"verdict":
///   {"kind": "armature", "status": "clear"}, "effects": [{"kind": "armature", "joint": "j",
///    "ambiguous_with": {"kind": "inertial_parameters", "point": "rod",
///                       "inseparable": "no motion separates them"}}]}}"#).unwrap();
/// let why = rivals::<Pendulum, 1>(&report).unwrap_err();
/// assert_eq!(why, "armature j vs inertial_parameters rod: no motion separates them");
/// ```
#[allow(clippy::type_complexity)]
pub fn rivals<R: Robot<N>, const N: usize>(
    report: &serde_json::Value,
) -> Result<(Vec<(excite::Rival, excite::Rival)>, Vec<String>), String> {
    let named = ambiguous_pairs(report);
    if named.is_empty() {
        return Err("the report names no ambiguous pair".into());
    }
    let marked = inseparable_pairs(report);
    let is_marked = |a: &(String, Option<String>), b: &(String, Option<String>)| {
        marked
            .iter()
            .find(|(x, y, _)| (x == a && y == b) || (x == b && y == a))
            .map(|(_, _, why)| why.clone())
    };
    let mut pairs = Vec::new();
    let mut labels = Vec::new();
    let mut left_out = Vec::new();
    for ((ka, pa), (kb, pb)) in &named {
        if let Some(why) = is_marked(&(ka.clone(), pa.clone()), &(kb.clone(), pb.clone())) {
            left_out.push(format!(
                "{ka} {} vs {kb} {}: {why}",
                pa.clone().unwrap_or_default(),
                pb.clone().unwrap_or_default()
            ));
            continue;
        }
        let rival = |k: &str, p: &Option<String>| {
            excite::Rival::named(k, p.as_deref(), &R::JOINT_NAMES, R::LINK_NAMES)
        };
        pairs.push((rival(ka, pa)?, rival(kb, pb)?));
        labels.push(format!(
            "{ka} {} vs {kb} {}",
            pa.clone().unwrap_or_default(),
            pb.clone().unwrap_or_default()
        ));
    }
    if pairs.is_empty() {
        return Err(left_out.join("; "));
    }
    Ok((pairs, labels))
}

/// For every ambiguous Coulomb-vs-Stribeck pair of a diagnosis report
/// (see [`ambiguous_pairs`]), the joint and how many times as much data of
/// the kind that made the report would settle the Stribeck fit's
/// breakaway excess (`data_needed` of the `which.ranked[]` entry of
/// `stribeck_friction` at the joint). A nested pair is not separated by
/// the motion's shape alone: the richer effect fits as well on any motion,
/// and only a tighter interval of its extra decides; that takes a longer
/// run.
///
/// ```
/// let report: serde_json::Value = serde_json::from_str(r#"{"which": {"verdict":
///   {"kind": "coulomb_friction", "joint": "j3", "status": "ambiguous",
///    "rival": {"kind": "stribeck_friction", "joint": "j3"}}, "effects": [],
///   "ranked": [{"kind": "stribeck_friction", "joint": "j3", "data_needed": 8.1}]}}"#).unwrap();
/// assert_eq!(dynamics_cli::excite::data_needed(&report), vec![("j3".to_string(), 8.1)]);
/// ```
pub fn data_needed(report: &serde_json::Value) -> Vec<(String, f64)> {
    let which = &report["which"];
    let mut out: Vec<(String, f64)> = Vec::new();
    for ((ka, pa), (kb, pb)) in ambiguous_pairs(report) {
        let kinds = [ka.as_str(), kb.as_str()];
        let (Some(joint), true) = (
            pa.clone().filter(|a| Some(a) == pb.as_ref()),
            kinds.contains(&"coulomb_friction") && kinds.contains(&"stribeck_friction"),
        ) else {
            continue;
        };
        let needed = which["ranked"]
            .as_array()
            .into_iter()
            .flatten()
            .find(|r| {
                r["kind"] == "stribeck_friction" && r["joint"].as_str() == Some(joint.as_str())
            })
            .and_then(|r| r["data_needed"].as_f64())
            .filter(|f| f.is_finite() && *f >= 1.0);
        if let Some(f) = needed {
            if !out.iter().any(|o| o.0 == joint) {
                out.push((joint, f));
            }
        }
    }
    out
}

/// The pairs a report marks as inseparable (`which.verdict.inseparable`
/// with its rival, `which.effects[].ambiguous_with.inseparable`), with the
/// reason.
#[allow(clippy::type_complexity)]
fn inseparable_pairs(
    report: &serde_json::Value,
) -> Vec<((String, Option<String>), (String, Option<String>), String)> {
    let entry = report_entry;
    let mut out = Vec::new();
    let which = &report["which"];
    let verdict = &which["verdict"];
    if let (Some(why), Some(a), Some(b)) = (
        verdict["inseparable"].as_str(),
        entry(verdict),
        entry(&verdict["rival"]),
    ) {
        out.push((a, b, why.to_string()));
    }
    for e in which["effects"].as_array().into_iter().flatten() {
        let rival = &e["ambiguous_with"];
        if let (Some(why), Some(a), Some(b)) =
            (rival["inseparable"].as_str(), entry(e), entry(rival))
        {
            out.push((a, b, why.to_string()));
        }
    }
    out
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
    o.clearance = args.clearance.then_some(excite::Clearance {
        ground: args.ground_clearance,
        distance: args.link_clearance,
    });
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
    let (d, separation) = match &args.separate {
        None => (excite::design(robot, &lim, &o)?, None),
        Some(path) => {
            let file = path.display().to_string();
            let text = std::fs::read_to_string(path).map_err(|e| format!("{file}: {e}"))?;
            let json: serde_json::Value =
                serde_json::from_str(&text).map_err(|e| format!("{file}: {e}"))?;
            let (pairs, labels) = rivals::<R, N>(&json).map_err(|e| format!("{file}: {e}"))?;
            let (d, angles) = excite::design_separating(robot, &lim, &o, &pairs)?;
            let rate = 200.0 / d.motion.period;
            let before = excite::separation_angles(
                robot,
                &d.columns,
                &pairs,
                &default_states::<N>(&info.motion, args.duration, rate, args.seed),
            )?;
            let mut rows = Vec::new();
            for (i, label) in labels.iter().enumerate() {
                println!(
                    "{label}: smallest principal angle, the others projected out: designed {:.2} deg, default sines {:.2} deg",
                    angles[i].to_degrees(),
                    before[i].to_degrees()
                );
                rows.push(serde_json::json!({
                    "pair": label,
                    "angle_deg": angles[i].to_degrees(),
                    "default_angle_deg": before[i].to_degrees(),
                }));
            }
            for (joint, f) in data_needed(&json) {
                let pair = |l: &str| {
                    l.contains("coulomb_friction")
                        && l.contains("stribeck_friction")
                        && l.split(' ').filter(|w| *w == joint).count() == 2
                };
                for (row, _) in rows.iter_mut().zip(&labels).filter(|(_, l)| pair(l)) {
                    row["data_needed"] = serde_json::json!(f);
                }
                if f > 1.0 {
                    println!(
                        "coulomb vs stribeck friction at {joint}: the report's data leave the breakaway excess undetermined; settling it takes about {f:.1} times as much data of that kind: a run {f:.1} times as long as the report's training record (repeat this design: --duration with --period {:.3})",
                        d.motion.period
                    );
                }
            }
            (d, Some(rows))
        }
    };
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
    if let Some(m) = &report.min_clearance {
        let at = |v: Option<f64>, w: Option<String>| match (v, w) {
            (Some(v), Some(w)) => format!("{v:.3} m ({w})"),
            _ => "not checked".into(),
        };
        println!(
            "clearance of the link frames' origins ({} frames, {} pairs checked; not meshes): lowest above the ground {}, closest pair {}",
            m.frames,
            m.pairs,
            at(m.ground, m.lowest.clone()),
            at(m.distance, m.closest.clone().map(|c| c.join(" - ")))
        );
    }
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
            "predicted: the least certain base parameter with a nominal value is {name} ({:.1} % relative standard deviation); {} columns stay unidentifiable alone",
            100.0 * r,
            report.identifiability.unidentifiable.len()
        );
    }
    println!("motion: {}", args.out.display());
    if let Some(path) = &args.plot {
        std::fs::write(path, plot(robot, &d)).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("plot: {}", path.display());
    }
    if let Some(path) = &args.json {
        let mut value = serde_json::to_value(&report)?;
        if let (Some(rows), Some(map)) = (separation, value.as_object_mut()) {
            map.insert("separation".into(), serde_json::Value::Array(rows));
        }
        let text = serde_json::to_string_pretty(&value)?;
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

/// `check-data`.
#[derive(Args, Debug, Clone)]
pub struct CheckDataArgs {
    /// The recorded (or designed) motion: CSV with `t`, `q_<joint>` and optionally
    /// `qd_<joint>` (else differentiated from the positions); other columns are skipped.
    #[arg(long)]
    pub data: PathBuf,
    /// Write the findings as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// The nominal model.
    #[command(flatten)]
    pub model: crate::tune::ModelArgs,
}

/// Times, positions and velocities of the CSV `text` (file name `file`):
/// `t`, `q_<joint>` and `qd_<joint>` when present, else central
/// differences of the positions.
///
/// ```
/// let (t, q, qd) = dynamics_cli::excite::read_motion::<1>("t,q_j\n0,0\n1,1\n2,4\n", &["j"], "m.csv").unwrap();
/// assert_eq!((t.len(), q[2][0], qd[1][0]), (3, 4.0, 2.0));
/// ```
#[allow(clippy::type_complexity)]
pub fn read_motion<const N: usize>(
    text: &str,
    joints: &[&str; N],
    file: &str,
) -> Result<(Vec<f64>, Vec<SVector<f64, N>>, Vec<SVector<f64, N>>), String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let header: Vec<&str> = lines
        .next()
        .map(|(_, l)| l.split(',').map(str::trim).collect())
        .ok_or(format!("{file}: empty"))?;
    let find = |name: &str| header.iter().position(|h| *h == name);
    let t_col = find("t").ok_or(format!("{file}: line 1: no column `t`"))?;
    let q_cols = joints
        .iter()
        .map(|j| find(&format!("q_{j}")).ok_or(format!("{file}: line 1: no column `q_{j}`")))
        .collect::<Result<Vec<_>, _>>()?;
    let qd_cols: Option<Vec<usize>> = joints.iter().map(|j| find(&format!("qd_{j}"))).collect();
    let (mut t, mut q, mut qd) = (Vec::new(), Vec::new(), Vec::new());
    for (i, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |c: usize| finite_cell(&cells, c, file, i + 1);
        t.push(num(t_col)?);
        let mut row = SVector::<f64, N>::zeros();
        for (j, &c) in q_cols.iter().enumerate() {
            row[j] = num(c)?;
        }
        q.push(row);
        if let Some(cols) = &qd_cols {
            let mut v = SVector::<f64, N>::zeros();
            for (j, &c) in cols.iter().enumerate() {
                v[j] = num(c)?;
            }
            qd.push(v);
        }
    }
    if t.len() < 3 {
        return Err(format!("{file}: {} rows, need at least 3", t.len()));
    }
    if qd_cols.is_none() {
        let n = t.len();
        qd = (0..n)
            .map(|k| {
                let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
                let dt = t[b] - t[a];
                if dt > 0.0 {
                    (q[b] - q[a]) / dt
                } else {
                    SVector::zeros()
                }
            })
            .collect();
    }
    Ok((t, q, qd))
}

/// The samples of a motion file (`t, q_<joint>, qd_<joint>, qdd_<joint>`,
/// as `excite --out` writes it; other columns skipped), named `file` in
/// errors.
///
/// ```
/// let s = dynamics_cli::excite::read_samples::<1>("t,q_j,qd_j,qdd_j\n0,1,0,0\n0.5,1.5,2,0\n", &["j"], "m.csv").unwrap();
/// assert_eq!((s.len(), s[1].0, s[1].1.qd[0]), (2, 0.5, 2.0));
/// assert!(dynamics_cli::excite::read_samples::<1>("t,q_j,qd_j\n0,1,0\n", &["j"], "m.csv").is_err());
/// ```
pub fn read_samples<const N: usize>(
    text: &str,
    joints: &[&str; N],
    file: &str,
) -> Result<Vec<(f64, Reference<N>)>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let header: Vec<&str> = lines
        .next()
        .map(|(_, l)| l.split(',').map(str::trim).collect())
        .ok_or(format!("{file}: empty"))?;
    let find = |name: String| {
        header
            .iter()
            .position(|h| *h == name)
            .ok_or(format!("{file}: line 1: no column `{name}`"))
    };
    let t_col = find("t".into())?;
    let cols = |p: &str| -> Result<Vec<usize>, String> {
        joints.iter().map(|j| find(format!("{p}_{j}"))).collect()
    };
    let (qc, qdc, qddc) = (cols("q")?, cols("qd")?, cols("qdd")?);
    let mut out = Vec::new();
    for (i, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |c: usize| finite_cell(&cells, c, file, i + 1);
        let vec = |cs: &[usize]| -> Result<SVector<f64, N>, String> {
            let mut v = SVector::<f64, N>::zeros();
            for (j, &c) in cs.iter().enumerate() {
                v[j] = num(c)?;
            }
            Ok(v)
        };
        out.push((
            num(t_col)?,
            Reference {
                q: vec(&qc)?,
                qd: vec(&qdc)?,
                qdd: vec(&qddc)?,
            },
        ));
    }
    if out.len() < 2 {
        return Err(format!("{file}: {} rows, need at least 2", out.len()));
    }
    Ok(out)
}

/// The designed motion and its duration from a design's JSON (what
/// `excite --json` writes: `joints`, `q0`, `period`, `duration`, `sin`,
/// `cos`), named `file` in errors; its joints must be `joints`.
///
/// ```
/// let text = r#"{"joints": ["j"], "q0": [0.5], "period": 2.0, "duration": 4.0,
///   "sin": [[0.1], [0.0], [0.0]], "cos": [[0.0], [0.0], [0.0]]}"#;
/// let (f, d) = dynamics_cli::excite::read_design::<1>(text, &["j"], "run.json").unwrap();
/// assert_eq!((f.harmonics(), f.q0[0], d), (3, 0.5, 4.0));
/// assert!(dynamics_cli::excite::read_design::<1>(text, &["k"], "run.json").is_err());
/// ```
pub fn read_design<const N: usize>(
    text: &str,
    joints: &[&str; N],
    file: &str,
) -> Result<(excite::Fourier<N>, f64), String> {
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| format!("{file}: {e}"))?;
    let names: Vec<&str> = v["joints"]
        .as_array()
        .map(|a| a.iter().filter_map(|x| x.as_str()).collect())
        .unwrap_or_default();
    if names != joints.as_slice() {
        return Err(format!(
            "{file}: designed for joints [{}], the robot has [{}]",
            names.join(", "),
            joints.join(", ")
        ));
    }
    let number = |key: &str| -> Result<f64, String> {
        v[key]
            .as_f64()
            .filter(|x| x.is_finite() && *x > 0.0)
            .ok_or(format!("{file}: `{key}` is not a positive number"))
    };
    let (period, duration) = (number("period")?, number("duration")?);
    let row = |x: &serde_json::Value, key: &str, k: usize| -> Result<SVector<f64, N>, String> {
        let a = x
            .as_array()
            .filter(|a| a.len() == N)
            .ok_or(format!("{file}: `{key}`[{k}] is not a list of {N} numbers"))?;
        let mut out = SVector::<f64, N>::zeros();
        for (j, e) in a.iter().enumerate() {
            out[j] = e
                .as_f64()
                .ok_or(format!("{file}: `{key}`[{k}][{j}] is not a number"))?;
        }
        Ok(out)
    };
    let q0 = row(&v["q0"], "q0", 0)?;
    let rows = |key: &str| -> Result<Vec<SVector<f64, N>>, String> {
        v[key]
            .as_array()
            .ok_or(format!("{file}: no list `{key}`"))?
            .iter()
            .enumerate()
            .map(|(k, x)| row(x, key, k))
            .collect()
    };
    let (sin, cos) = (rows("sin")?, rows("cos")?);
    if sin.len() != cos.len() {
        return Err(format!(
            "{file}: {} sine and {} cosine harmonics",
            sin.len(),
            cos.len()
        ));
    }
    Ok((
        excite::Fourier {
            q0,
            period,
            sin,
            cos,
        },
        duration,
    ))
}

/// `check-data` on `robot` (the nominal model): what the motion in
/// `args.data` can and cannot identify, in words.
pub fn check_data_cmd<R: Robot<N>, const N: usize>(
    robot: &R,
    info: &crate::RobotInfo,
    args: &CheckDataArgs,
) -> Res {
    let file = args.data.display().to_string();
    let text = std::fs::read_to_string(&args.data).map_err(|e| format!("{file}: {e}"))?;
    let (t, q, qd) = read_motion::<N>(&text, &R::JOINT_NAMES, &file)?;
    let lim = limits::<N>(info.limits.as_ref(), &info.motion);
    let columns = dynamics_sim2real::excite::BaseColumns::of(robot, &lim, 1)?;
    let c = excite::check_data(robot, &columns, &t, &q, &qd)?;
    println!(
        "{file}: {} samples over {:.2} s; condition number of the base regressor ({} base parameters, friction, rotor inertia and offsets included): {:.1}",
        t.len(),
        t[t.len() - 1] - t[0],
        columns.kept.len(),
        c.condition
    );
    for j in &c.joints {
        println!(
            "  {:16} {:3} reversals, peak velocity {:.3}, {:.1} % of the time slow, range [{:.3}, {:.3}]",
            j.joint,
            j.reversals,
            j.peak_velocity,
            100.0 * j.slow_fraction,
            j.range[0],
            j.range[1]
        );
    }
    if c.words.is_empty() {
        println!("nothing stands out: every joint reverses often and moves fast enough, and no direction of the parameters is 100 times weaker than the strongest");
    }
    for w in &c.words {
        println!("- {w}");
    }
    if let Some(path) = &args.json {
        std::fs::write(path, serde_json::to_string_pretty(&c)?)
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

/// Cell `c` (0-based) of a CSV line split into `cells`, as a finite
/// number; `Err` names the file, the line (1-based) and the column.
fn finite_cell(cells: &[&str], c: usize, file: &str, line: usize) -> Result<f64, String> {
    cells
        .get(c)
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|v| v.is_finite())
        .ok_or(format!(
            "{file}: line {line}: column {} is not a finite number",
            c + 1
        ))
}
