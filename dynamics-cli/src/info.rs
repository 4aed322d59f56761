//! What the program knows about a robot besides its model: its name,
//! reference states and motion. Every subcommand reads it; the program
//! (`program/`) fills it in.

use crate::gap::Motion;

/// What the program knows about a robot besides its model.
#[derive(Debug, Clone, Default)]
pub struct RobotInfo {
    /// The name it goes by (`--robot NAME`, reports, truth files).
    pub name: String,
    /// Reference states (file name, JSON text in the format of
    /// Pinocchio's reference files): the default states of `eval`.
    pub states: Option<(String, String)>,
    /// Whether `states` carry reference values of this very model (what
    /// `check` compares against).
    pub reference_values: bool,
    /// Home pose and amplitudes for `synth` and `simulate`.
    pub motion: Motion,
    /// Joint limits (a URDF robot's `LOWER`, `UPPER`, `VELOCITY`,
    /// `EFFORT`), for `excite`; `None`: the robot has none.
    pub limits: Option<JointLimits>,
}

/// Per-joint limits as a URDF gives them (`f64::INFINITY` where none).
///
/// ```
/// let l = dynamics_cli::JointLimits::of([-1.0], [1.0], [2.0], [3.0]);
/// assert_eq!(l.effort, vec![3.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct JointLimits {
    /// Lower position limits.
    pub lower: Vec<f64>,
    /// Upper position limits.
    pub upper: Vec<f64>,
    /// Velocity limits.
    pub velocity: Vec<f64>,
    /// Effort limits.
    pub effort: Vec<f64>,
}

impl JointLimits {
    /// From the four arrays `robot!` emits for a URDF robot.
    pub fn of<const N: usize>(
        lower: [f64; N],
        upper: [f64; N],
        velocity: [f64; N],
        effort: [f64; N],
    ) -> Self {
        JointLimits {
            lower: lower.to_vec(),
            upper: upper.to_vec(),
            velocity: velocity.to_vec(),
            effort: effort.to_vec(),
        }
    }
}
