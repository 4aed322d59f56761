//! Sim-to-real gap work on one robot: synthetic measured data with a
//! withheld effect (`dynamics synth`, `synth/`) and the diagnosis of
//! data files (`dynamics diagnose`, `files.rs`).

mod files;
mod source;
mod synth;

pub use files::{
    diagnose_calibrated, diagnose_data, diagnose_data_described, diagnose_files, traces_calibrated,
    traces_data, traces_files,
};
pub use source::{parse_window, DataFile};
pub use synth::{
    holdout_window, synth, synth_following, synth_recorded, Motion, Recording, SynthOutput,
    SynthRequest, Truth, TruthWindow,
};

use dynamics_sim2real::data::bag::BagError;
use dynamics_sim2real::data::import::ImportError;
use dynamics_sim2real::data::DataError;
use dynamics_sim2real::diagnose::traces::TracesError;
use dynamics_sim2real::diagnose::DiagnoseError;
use dynamics_sim2real::synth::SynthError;
use thiserror::Error;

/// Why a gap command failed.
#[derive(Debug, Error)]
pub enum GapError {
    /// No robot of that name (a program over several robots).
    #[error("unknown robot `{name}`; known robots: {known}")]
    UnknownRobot {
        /// The name asked for.
        name: String,
        /// The known names, comma-separated.
        known: String,
    },
    /// Reading data.
    #[error(transparent)]
    Data(#[from] DataError),
    /// Reading a recorded file through a column map.
    #[error(transparent)]
    Import(#[from] ImportError),
    /// Reading a ROS 2 bag or a Parquet file.
    #[error(transparent)]
    Bag(#[from] BagError),
    /// Generating data.
    #[error(transparent)]
    Synth(#[from] SynthError),
    /// Diagnosing.
    #[error(transparent)]
    Diagnose(#[from] DiagnoseError),
    /// Time series for the readable report.
    #[error(transparent)]
    Traces(#[from] TracesError),
    /// A bad request.
    #[error("{0}")]
    Request(String),
}
