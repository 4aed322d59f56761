//! The readable diagnosis report (`dynamics diagnose --report DIR`):
//! `report.md` stating where, which and how far it shrinks, with SVG
//! figures beside it (per joint: the training residual with the gap
//! windows shaded, the held-out residual before and after the chosen
//! effect, measured vs nominal vs corrected effort; the ranking), and
//! `report.json`.

pub mod explanation;
mod figures;
mod markdown;

use std::path::{Path, PathBuf};

use dynamics_sim2real::diagnose::traces::Traces;
use dynamics_sim2real::diagnose::{Options, Report};
use thiserror::Error;

pub use markdown::GAP_RATIO;

/// Why a report could not be written.
#[derive(Debug, Error)]
pub enum ReportError {
    /// Creating the folder or writing a file.
    #[error("{path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// Serialising the JSON.
    #[error("report.json: {0}")]
    Json(#[from] serde_json::Error),
}

/// A file name made of a joint name (anything but letters, digits, `-`
/// and `_` becomes `_`).
fn slug(joint: &str) -> String {
    joint
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn joint_files(joint: &str) -> [String; 3] {
    let j = slug(joint);
    [
        format!("residual-{j}.svg"),
        format!("shrink-{j}.svg"),
        format!("effort-{j}.svg"),
    ]
}

/// The report's files: `(name, content)`, `report.md` first.
///
/// ```no_run
/// use dynamics_sim2real::diagnose::Options;
/// use std::path::Path;
/// dynamics_macros::robot! {
///     pub robot Arm; gravity = [0.0, -9.81, 0.0];
///     link base; link a { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     link b { mass = 0.5; com = [0.15, 0.0, 0.0]; inertia = [1e-3, 5e-3, 5e-3]; }
///     joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(a -> b) { transfer = [tu(0.4), rot_z(q)]; }
/// }
/// let arm = Arm::default();
/// let options = Options::default();
/// let (report, _warnings) = dynamics_cli::gap::diagnose_files(
///     &arm, Path::new("train.csv"), Path::new("holdout.csv"), &options, &|_, _| {})?;
/// let traces = dynamics_cli::gap::traces_files(
///     &arm, Path::new("train.csv"), Path::new("holdout.csv"), &report, &options)?;
/// let files = dynamics_cli::report::render(&report, &traces, &options);
/// assert_eq!(files[0].0, "report.md");
/// # Ok::<(), dynamics_cli::gap::GapError>(())
/// ```
pub fn render(report: &Report, traces: &Traces, options: &Options) -> Vec<(String, String)> {
    let corrected = !traces.explained.is_empty() || report.which.verdict.names_effect();
    let mut out = vec![(
        "report.md".to_string(),
        markdown::markdown(report, traces, options, &joint_files),
    )];
    for (j, gap) in report.where_.joints.iter().enumerate() {
        let (Some(train), Some(hold)) = (traces.train.joints.get(j), traces.holdout.joints.get(j))
        else {
            continue;
        };
        let [residual, shrink, effort] = joint_files(&gap.joint);
        out.push((
            residual,
            figures::residual(&traces.train, train, gap, corrected),
        ));
        out.push((shrink, figures::shrink(&traces.holdout, hold)));
        out.push((effort, figures::effort(&traces.holdout, hold)));
    }
    out.push((
        "ranking.svg".into(),
        figures::ranking(report, options.none_margin),
    ));
    if !report.shrink.steps.is_empty() {
        out.push(("explanation.svg".into(), explanation::chart(report)));
    }
    out
}

/// Writes [`render`]'s files and `report.json` into `dir` (created if
/// missing); returns the paths written.
///
/// ```
/// use dynamics_sim2real::diagnose::Options;
/// use dynamics_sim2real::effects::EffectKind;
/// use dynamics_cli::gap::{diagnose_files, synth, traces_files, Motion, SynthRequest};
/// dynamics_macros::robot! {
///     pub robot Arm; gravity = [0.0, -9.81, 0.0];
///     link base; link a { mass = 1.0; com = [0.2, 0.0, 0.0]; inertia = [1e-3, 1e-2, 1e-2]; }
///     link b { mass = 0.5; com = [0.15, 0.0, 0.0]; inertia = [1e-3, 5e-3, 5e-3]; }
///     joint j1 = revolute(base -> a) { transfer = [rot_z(q)]; }
///     joint j2 = revolute(a -> b) { transfer = [tu(0.4), rot_z(q)]; }
/// }
/// let arm = Arm::default();
/// let dir = std::env::temp_dir().join(format!("dynamics-report-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let data = synth(&arm, &Motion::default(), &SynthRequest {
///     robot: "arm".into(), kind: Some(EffectKind::ViscousFriction), joint: Some("j2".into()),
///     magnitude: Some(0.5), seed: 3, excitation: "sines".parse().unwrap(), duration: 2.0,
///     noise: Default::default(),
/// })?;
/// let (train, holdout) = (dir.join("train.csv"), dir.join("holdout.csv"));
/// std::fs::write(&train, &data.train)?;
/// std::fs::write(&holdout, &data.holdout)?;
/// let options = Options::default();
/// let (report, _warnings) = diagnose_files(&arm, &train, &holdout, &options, &|_, _| {})?;
/// let traces = traces_files(&arm, &train, &holdout, &report, &options)?;
/// let written = dynamics_cli::report::write(&dir.join("report"), &report, &traces, &options)?;
/// assert!(written.iter().any(|p| p.ends_with("report.md")));
/// assert!(written.iter().any(|p| p.ends_with("residual-j2.svg")));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write(
    dir: &Path,
    report: &Report,
    traces: &Traces,
    options: &Options,
) -> Result<Vec<PathBuf>, ReportError> {
    write_described(dir, report, traces, options, &[])
}

/// [`write`], with lines saying what was read (a bag's topic, message count
/// and time range: [`crate::gap::diagnose_data_described`]) under the
/// report's title.
pub fn write_described(
    dir: &Path,
    report: &Report,
    traces: &Traces,
    options: &Options,
    about: &[String],
) -> Result<Vec<PathBuf>, ReportError> {
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |source| ReportError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let mut files = render(report, traces, options);
    if let (Some((_, md)), false) = (files.first_mut(), about.is_empty()) {
        // After the title line and its blank line.
        let at = md.find("\n\n").map_or(0, |i| i + 2);
        let lines: String = about.iter().map(|l| format!("- {l}\n")).collect();
        md.insert_str(at, &format!("Recorded data read:\n\n{lines}\n"));
    }
    files.push((
        "report.json".into(),
        serde_json::to_string_pretty(report)? + "\n",
    ));
    let mut written = Vec::new();
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(io(&path))?;
        written.push(path);
    }
    Ok(written)
}
