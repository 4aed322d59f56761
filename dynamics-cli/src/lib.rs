//! The generic `dynamics` command-line program over any robot written with
//! `robot!`: its subcommands (`commands`, `diagnose`, `identify`), evaluation at given
//! states and comparison with reference values (`eval`, `states`,
//! `compare`), synthetic data and the diagnosis of data files (`gap`), the
//! readable diagnosis report (`report`) and SVG plots (`plot`).
//!
//! Nothing here knows a particular robot: the built-in robots and their
//! by-name dispatch live in the crate `robots`.

pub mod commands;
pub mod compare;
pub mod diagnose;
pub mod eval;
pub mod gap;
pub mod identify;
pub mod plot;
pub mod report;
pub mod states;

/// What every subcommand returns; `main` prints the error.
pub type Res = Result<(), Box<dyn std::error::Error>>;
