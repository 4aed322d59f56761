//! The generic `dynamics` command-line program over any robot written with
//! `robot!`: [`run`] is the whole program over one robot (a user's crate
//! needs nothing else), [`run_set`] over robots chosen by name
//! (`program`: the command line and its dispatch); its subcommands
//! (`commands`, `diagnose`, `identify`, `simulate`, `excite`, `scaffold` for `new`), the nominal
//! model (`tune`: `--set`, `--baseline`), what the program knows of a robot
//! besides its model (`info`), evaluation at given
//! states and comparison with reference values (`eval`, `states`,
//! `compare`), synthetic data and the diagnosis of data files (`gap`), the
//! readable diagnosis report (`report`) and SVG plots (`plot`), warnings
//! as lines (`warnings`).
//!
//! Nothing here knows a particular robot: the built-in robots and their
//! by-name dispatch live in the crate `robots`.

pub mod commands;
pub mod compare;
pub mod diagnose;
pub mod eval;
pub mod excite;
pub mod gap;
pub mod identify;
pub mod info;
pub mod plot;
pub mod program;
pub mod report;
pub mod scaffold;
pub mod simulate;
pub mod states;
pub mod tune;
pub mod warnings;

pub use info::{JointLimits, RobotInfo};
pub use program::{run, run_set, run_with, RobotSet, RobotVisitor};

/// What every subcommand returns; `main` prints the error.
pub type Res = Result<(), Box<dyn std::error::Error>>;
