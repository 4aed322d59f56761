//! Robots by name, for the command-line program.

use dynamics_runtime::{DynamicsError, Parameters, Robot};
use thiserror::Error;

use crate::{Arm3r, Arm3rUrdf, Mar, MarUrdf, Panda, PandaArm, Rrp, RrpUrdf, Ur5};
use dynamics_cli::eval::{evaluate, Evaluated};
use dynamics_cli::states::{self, StatesError};

/// Names the command-line program knows, with a line each.
pub const ROBOTS: &[(&str, &str)] = &[
    (
        "arm3r",
        "planar 3R loading arm, dissertation, sec. 3.1.1 (3 DOF)",
    ),
    (
        "rrp",
        "planar RRP arm with plunger spring and drag, dissertation, sec. 3.1.2 (3 DOF)",
    ),
    (
        "rrp-rigid",
        "the RRP arm without spring and drag, as Pinocchio models it (3 DOF)",
    ),
    (
        "mar",
        "MAR manipulator, vibration paper, Table 1, rigid (3 DOF)",
    ),
    (
        "mar-drives",
        "MAR with Table 1's drive stiffness and damping (3 DOF)",
    ),
    ("ur5", "Universal Robots UR5 from its URDF (6 DOF)"),
    ("panda", "Franka Emika Panda from its URDF, rigid (7 DOF)"),
    (
        "panda-damped",
        "the Panda with the URDF's joint damping (7 DOF)",
    ),
    (
        "panda-arm",
        "the Panda without its hand, as in Gaz et al.'s logs (7 DOF)",
    ),
    ("arm3r-urdf", "arm3r read from its URDF (3 DOF)"),
    ("rrp-urdf", "the RRP arm read from its URDF, rigid (3 DOF)"),
    ("mar-urdf", "the MAR read from its URDF (3 DOF)"),
];

/// A robot chosen by name.
#[derive(Debug, Clone)]
pub enum AnyRobot {
    /// [`Arm3r`]
    Arm3r(Arm3r),
    /// [`Rrp`]
    Rrp(Rrp),
    /// [`Mar`]
    Mar(Mar),
    /// [`Ur5`]
    Ur5(Ur5),
    /// [`Panda`]
    Panda(Panda),
    /// [`PandaArm`]
    PandaArm(PandaArm),
    /// [`Arm3rUrdf`]
    Arm3rUrdf(Arm3rUrdf),
    /// [`RrpUrdf`]
    RrpUrdf(RrpUrdf),
    /// [`MarUrdf`]
    MarUrdf(MarUrdf),
}

/// What the registry can fail with.
#[derive(Debug, Error)]
pub enum RegistryError {
    /// No robot of that name.
    #[error("unknown robot `{0}`; known robots: {known}", known = ROBOTS.iter().map(|r| r.0).collect::<Vec<_>>().join(", "))]
    UnknownRobot(String),
    /// A parameter could not be set.
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// The states could not be read.
    #[error(transparent)]
    States(#[from] StatesError),
}

/// Runs `$body` with `$r` bound to the concrete robot inside an [`AnyRobot`].
#[macro_export]
#[doc(hidden)]
macro_rules! each_robot {
    ($self:expr, $r:ident => $body:expr) => {
        match $self {
            $crate::registry::AnyRobot::Arm3r($r) => $body,
            $crate::registry::AnyRobot::Rrp($r) => $body,
            $crate::registry::AnyRobot::Mar($r) => $body,
            $crate::registry::AnyRobot::Ur5($r) => $body,
            $crate::registry::AnyRobot::Panda($r) => $body,
            $crate::registry::AnyRobot::PandaArm($r) => $body,
            $crate::registry::AnyRobot::Arm3rUrdf($r) => $body,
            $crate::registry::AnyRobot::RrpUrdf($r) => $body,
            $crate::registry::AnyRobot::MarUrdf($r) => $body,
        }
    };
}

macro_rules! each {
    ($self:expr, $r:ident => $body:expr) => {
        match $self {
            AnyRobot::Arm3r($r) => $body,
            AnyRobot::Rrp($r) => $body,
            AnyRobot::Mar($r) => $body,
            AnyRobot::Ur5($r) => $body,
            AnyRobot::Panda($r) => $body,
            AnyRobot::PandaArm($r) => $body,
            AnyRobot::Arm3rUrdf($r) => $body,
            AnyRobot::RrpUrdf($r) => $body,
            AnyRobot::MarUrdf($r) => $body,
        }
    };
}

impl AnyRobot {
    /// The robot called `name` (see [`ROBOTS`]).
    ///
    /// ```
    /// let r = robots::registry::AnyRobot::by_name("rrp-rigid").unwrap();
    /// assert_eq!(r.joint_names(), vec!["q1", "q2", "q3"]);
    /// assert!(robots::registry::AnyRobot::by_name("r2d2").is_err());
    /// ```
    pub fn by_name(name: &str) -> Result<Self, RegistryError> {
        Ok(match name {
            "arm3r" => AnyRobot::Arm3r(Arm3r::default()),
            "rrp" => AnyRobot::Rrp(Rrp::default()),
            "rrp-rigid" => AnyRobot::Rrp(Rrp::rigid()),
            "mar" => AnyRobot::Mar(Mar::default()),
            "mar-drives" => AnyRobot::Mar(Mar::with_drives([0.0; 3])),
            "ur5" => AnyRobot::Ur5(Ur5::default()),
            "panda" => AnyRobot::Panda(Panda::rigid()),
            "panda-damped" => AnyRobot::Panda(Panda::default()),
            "panda-arm" => AnyRobot::PandaArm(PandaArm::rigid()),
            "arm3r-urdf" => AnyRobot::Arm3rUrdf(Arm3rUrdf::default()),
            "rrp-urdf" => AnyRobot::RrpUrdf(RrpUrdf::rigid()),
            "mar-urdf" => AnyRobot::MarUrdf(MarUrdf::default()),
            other => return Err(RegistryError::UnknownRobot(other.to_string())),
        })
    }

    /// The joint limits of a URDF robot (`None` for the robots written by
    /// hand, whose descriptions have none).
    ///
    /// ```
    /// use robots::registry::AnyRobot;
    /// let l = AnyRobot::by_name("panda").unwrap().limits().unwrap();
    /// assert_eq!(l.effort[0], 87.0);
    /// assert!(AnyRobot::by_name("arm3r").unwrap().limits().is_none());
    /// ```
    pub fn limits(&self) -> Option<dynamics_cli::JointLimits> {
        macro_rules! of {
            ($t:ty) => {
                Some(dynamics_cli::JointLimits::of(
                    <$t>::LOWER,
                    <$t>::UPPER,
                    <$t>::VELOCITY,
                    <$t>::EFFORT,
                ))
            };
        }
        match self {
            AnyRobot::Ur5(_) => of!(Ur5),
            AnyRobot::Panda(_) => of!(Panda),
            AnyRobot::PandaArm(_) => of!(PandaArm),
            AnyRobot::Arm3rUrdf(_) => of!(Arm3rUrdf),
            AnyRobot::RrpUrdf(_) => of!(RrpUrdf),
            AnyRobot::MarUrdf(_) => of!(MarUrdf),
            AnyRobot::Arm3r(_) | AnyRobot::Rrp(_) | AnyRobot::Mar(_) => None,
        }
    }

    /// Joint names in coordinate order.
    pub fn joint_names(&self) -> Vec<&'static str> {
        fn names<R: Robot<N>, const N: usize>(_: &R) -> Vec<&'static str> {
            R::JOINT_NAMES.to_vec()
        }
        each!(self, r => names(r))
    }

    /// Sets a run-time parameter by name.
    pub fn set_param(&mut self, name: &str, value: f64) -> Result<(), RegistryError> {
        each!(self, r => r.params.set(name, value)?);
        Ok(())
    }

    /// Reads states from JSON text and evaluates every quantity there.
    pub fn evaluate_json(&self, text: &str, file: &str) -> Result<Vec<Evaluated>, RegistryError> {
        let n = self.joint_names().len();
        let states = states::parse(text, file, n)?;
        Ok(each!(self, r => evaluate(r, &states)?))
    }

    /// The Pinocchio reference states shipped for this robot's rigid body
    /// (`panda-arm` shares the Panda's states; its values are the hand's
    /// model, so `dynamics check` leaves it out).
    pub fn reference(&self) -> (&'static str, &'static str) {
        match self {
            AnyRobot::Arm3r(_) | AnyRobot::Arm3rUrdf(_) => {
                ("arm3r.json", include_str!("../data/pinocchio/arm3r.json"))
            }
            AnyRobot::Rrp(_) | AnyRobot::RrpUrdf(_) => {
                ("rrp.json", include_str!("../data/pinocchio/rrp.json"))
            }
            AnyRobot::Mar(_) | AnyRobot::MarUrdf(_) => {
                ("mar.json", include_str!("../data/pinocchio/mar.json"))
            }
            AnyRobot::Ur5(_) => ("ur5.json", include_str!("../data/pinocchio/ur5.json")),
            AnyRobot::Panda(_) | AnyRobot::PandaArm(_) => {
                ("panda.json", include_str!("../data/pinocchio/panda.json"))
            }
        }
    }
}
