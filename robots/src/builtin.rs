//! The generic sim-to-real commands of `dynamics_cli::gap` over the
//! built-in robots by name, with each robot's home pose and amplitudes.

use std::path::Path;

use dynamics_cli::gap::{self, GapError, Motion, SynthOutput, SynthRequest};
use dynamics_sim2real::diagnose::traces::Traces;
use dynamics_sim2real::diagnose::{Options, Report};

use crate::registry::{AnyRobot, RegistryError, ROBOTS};

/// Home pose and reference amplitude of a built-in robot's motion (inside
/// the joint limits of the URDF arms); others move by 0.4 about zero.
///
/// ```
/// assert_eq!(robots::builtin::motion("ur5").home.len(), 6);
/// assert!(robots::builtin::motion("r2d2").home.is_empty());
/// ```
pub fn motion(name: &str) -> Motion {
    let (home, amplitude) = match name {
        "arm3r" | "arm3r-urdf" => (vec![0.0, 0.4, -0.4], vec![0.6, 0.6, 0.6]),
        "rrp" | "rrp-rigid" | "rrp-urdf" => (vec![0.0, 0.3, 0.05], vec![0.5, 0.5, 0.04]),
        "mar" | "mar-drives" | "mar-urdf" => (vec![0.0, 0.3, 0.05], vec![0.4, 0.5, 0.04]),
        "ur5" => (vec![0.0, -1.2, 1.2, -1.5, -1.5, 0.0], vec![0.4; 6]),
        "panda" | "panda-damped" => (vec![0.0, -0.4, 0.0, -2.0, 0.0, 1.7, 0.8], vec![0.35; 7]),
        _ => (Vec::new(), Vec::new()),
    };
    Motion { home, amplitude }
}

fn robot(name: &str) -> Result<AnyRobot, GapError> {
    AnyRobot::by_name(name).map_err(|e| match e {
        RegistryError::UnknownRobot(name) => GapError::UnknownRobot {
            name,
            known: ROBOTS.iter().map(|r| r.0).collect::<Vec<_>>().join(", "),
        },
        other => GapError::Request(other.to_string()),
    })
}

/// [`gap::synth`] for the built-in robot `req.robot`.
///
/// ```
/// use dynamics_sim2real::effects::EffectKind;
/// use dynamics_cli::gap::SynthRequest;
/// let out = robots::builtin::synth(&SynthRequest {
///     robot: "arm3r".into(), kind: Some(EffectKind::ViscousFriction), joint: Some("j2".into()),
///     magnitude: Some(0.5), seed: 3, excitation: "sines".parse().unwrap(), duration: 0.5,
///     noise: Default::default(),
/// }).unwrap();
/// assert!(out.train.starts_with("t,q_j1,q_j2,q_j3,qd_j1"));
/// assert_eq!(out.truth.kind, "viscous_friction");
/// ```
pub fn synth(req: &SynthRequest) -> Result<SynthOutput, GapError> {
    let motion = motion(&req.robot);
    crate::each_robot!(&robot(&req.robot)?, r => gap::synth(r, &motion, req))
}

/// [`gap::diagnose_files`] for the built-in robot `name`.
pub fn diagnose_files(
    name: &str,
    train: &Path,
    holdout: &Path,
    options: &Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Report, Vec<String>), GapError> {
    crate::each_robot!(&robot(name)?, r => gap::diagnose_files(r, train, holdout, options, progress))
}

/// [`gap::traces_files`] for the built-in robot `name`.
pub fn traces_files(
    name: &str,
    train: &Path,
    holdout: &Path,
    report: &Report,
    options: &Options,
) -> Result<Traces, GapError> {
    crate::each_robot!(&robot(name)?, r => gap::traces_files(r, train, holdout, report, options))
}
