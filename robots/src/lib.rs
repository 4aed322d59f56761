//! The robots of the source works (docs/references.md) written with
//! `robot!`, UR5 and Panda from their URDF, the scenarios of the source
//! works, and the built-in `dynamics` program: the generic program of
//! `dynamics-cli` over these robots by name (`registry`, `builtin`).
//!
//! | name | robot | source |
//! |---|---|---|
//! | `arm3r` | [`Arm3r`] | dissertation, sec. 3.1.1 / ch. 4, planar 3R loading arm |
//! | `rrp` | [`Rrp`] | dissertation, sec. 3.1.2, planar arm with plunger, spring and drag |
//! | `rrp-rigid` | [`Rrp::rigid`] | the same without spring and drag (Pinocchio's model) |
//! | `mar` | [`Mar`] | vibration paper, Table 1, rigid |
//! | `mar-drives` | [`Mar::with_drives`] | with Table 1's drive stiffness and damping |
//! | - | [`ClearanceArm`], [`ClearanceArmFree`] | dissertation, sec. 3.2, two links with joint clearance |
//! | - | [`ElasticGrip`] | dissertation, sec. 3.3, arm with an elastic push rod |
//! | - | [`Piston`] | dissertation, sec. 3.4, RRP arm whose piston end follows KL |

pub mod arm3r;
pub mod builtin;
pub mod clearance_arm;
pub mod elastic_grip;
pub mod mar;
pub mod piston;
pub mod registry;
pub mod rrp;
pub mod scenarios;
pub mod urdf_robots;

pub use arm3r::{Arm3r, Arm3rParams};
pub use clearance_arm::{ClearanceArm, ClearanceArmFree};
pub use elastic_grip::{ElasticGrip, ElasticGripParams};
pub use mar::{Mar, MarParams};
pub use piston::{Piston, PistonParams};
pub use rrp::{Rrp, RrpParams};
pub use urdf_robots::{
    Arm3rUrdf, MarUrdf, Panda, PandaArm, PandaParams, PandaPayload, RrpUrdf, Ur5, Ur5Params,
};

/// The README's examples, compiled and run as doc tests.
#[doc = include_str!("../../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

/// The examples of docs/robot-macro.md, compiled and run as doc tests.
#[doc = include_str!("../../docs/robot-macro.md")]
#[cfg(doctest)]
pub struct RobotMacroDoctests;

/// The examples of docs/runtime.md, compiled and run as doc tests.
#[doc = include_str!("../../docs/runtime.md")]
#[cfg(doctest)]
pub struct RuntimeDoctests;
