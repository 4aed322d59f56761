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
}
