//! The command line: subcommands and flags, the same for one robot and for
//! a set of robots (which adds `--robot NAME`, `list` and `new`).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

pub use crate::tune::{BaselineArgs, ModelArgs};

/// The program over one robot.
#[derive(Parser, Debug)]
#[command(
    version,
    about = "Equations of motion generated at compile time: evaluate, simulate, generate data, diagnose the sim-to-real gap."
)]
pub struct SingleCli {
    /// What to do.
    #[command(subcommand)]
    pub command: Option<RobotCommand>,
}

/// The program over a set of robots.
#[derive(Parser, Debug)]
#[command(
    version,
    about = "Equations of motion generated at compile time: evaluate, simulate, generate data, diagnose the sim-to-real gap."
)]
pub struct SetCli {
    /// What to do.
    #[command(subcommand)]
    pub command: Option<SetCommand>,
}

/// Subcommands of the program over a set of robots.
#[derive(Subcommand, Debug)]
pub enum SetCommand {
    /// The subcommands on one robot (chosen with `--robot`).
    #[command(flatten)]
    Robot(RobotCommand),
    /// List the robots.
    List,
    /// Write a crate for your own robot from its URDF: the whole program for it, with one call.
    New(crate::scaffold::NewArgs),
}

/// Subcommands on one robot.
#[derive(Subcommand, Debug)]
pub enum RobotCommand {
    /// Compare the model with reference values (Pinocchio's format).
    Check(CheckArgs),
    /// Evaluate tau, M, g, C, nle, ddq, K, D and the energies at given states.
    Eval(EvalArgs),
    /// Simulate the robot under a computed-torque controller following a reference; CSV + SVG plots.
    Simulate(crate::simulate::SimulateArgs),
    /// Generate measured data (CSV) of the robot with a withheld effect under a tracking controller.
    Synth(SynthArgs),
    /// Diagnose the gap between the model and measured data: where, which effect, how far it shrinks.
    Diagnose(DiagnoseArgs),
    /// Identify friction, offsets, rotor inertias and link inertial parameters by least squares.
    Identify(IdentifyArgs),
    /// Design an exciting motion within the robot's limits: CSV of t, q, qd, qdd and its design as JSON.
    Excite(crate::excite::ExciteArgs),
    /// Say what a recorded motion can and cannot identify: reversals, velocity range, weak directions.
    CheckData(crate::excite::CheckDataArgs),
}

/// `identify`.
#[derive(Args, Debug)]
pub struct IdentifyArgs {
    /// Training data: CSV or CSV.gz, Parquet, or a ROS 2 bag (a rosbag2 directory, .mcap or
    /// .db3).
    #[arg(long)]
    pub train: PathBuf,
    /// Held-out data.
    #[arg(long)]
    pub holdout: PathBuf,
    /// The topic of sensor_msgs/msg/JointState messages read from a ROS 2 bag
    /// (default /joint_states).
    #[arg(long, value_name = "NAME")]
    pub topic: Option<String>,
    /// Write the result as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// The nominal model.
    #[command(flatten)]
    pub model: ModelArgs,
}

/// `check`.
#[derive(Args, Debug)]
pub struct CheckArgs {
    /// Reference file (`states: [{q, v, a, tau, M, ...}]`); default: the robot's shipped one.
    #[arg(long, value_name = "FILE.json")]
    pub reference: Option<PathBuf>,
    /// The nominal model.
    #[command(flatten)]
    pub model: ModelArgs,
}

/// `eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// States file (JSON with `states: [{q, v, a}]`); default: the robot's reference states.
    #[arg(long)]
    pub states: Option<PathBuf>,
    /// Where to write the JSON; default: standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The nominal model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// A calibrated baseline.
    #[command(flatten)]
    pub baseline: BaselineArgs,
}

/// `synth`.
#[derive(Args, Debug)]
pub struct SynthArgs {
    /// Effect kind (coulomb_friction, viscous_friction, stribeck_friction, armature, payload_mass,
    /// joint_elasticity, backlash, environment_resistance, encoder_offset, time_delay, none);
    /// omit to draw one at random.
    #[arg(long)]
    pub effect: Option<String>,
    /// Joint name; omit to draw one.
    #[arg(long)]
    pub joint: Option<String>,
    /// Main parameter in SI units (Fc, Fv, Fc, rotor inertia, kg, resonance Hz, half-width,
    /// mu, offset, delay s); omit to draw from the realistic range.
    #[arg(long)]
    pub magnitude: Option<f64>,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Reference motion: sines, chirp or pick-place (drawn with the seed), or a design's JSON
    /// (`dynamics excite --json run.json`: the training run follows the designed motion over
    /// its duration; the held-out run follows sines).
    #[arg(long, default_value = "sines")]
    pub excitation: String,
    /// The training run follows this motion (CSV: t, q_<joint>, qd_<joint>, qdd_<joint>, as
    /// `dynamics excite --out` writes it) over its duration; the held-out run follows sines.
    #[arg(long, value_name = "MOTION.csv", conflicts_with = "excitation")]
    pub motion: Option<PathBuf>,
    /// Duration, s (with a designed motion or a motion file: theirs).
    #[arg(long, default_value_t = 8.0)]
    pub duration: f64,
    /// Position noise (rad or m).
    #[arg(long, default_value_t = 2e-5)]
    pub noise_q: f64,
    /// Velocity noise.
    #[arg(long, default_value_t = 2e-3)]
    pub noise_qd: f64,
    /// Effort noise as a fraction of each joint's peak effort.
    #[arg(long, default_value_t = 2e-3)]
    pub noise_tau: f64,
    /// Training data to write: CSV, or Parquet when named `.parquet` (the held-out set goes
    /// beside it as `<stem>-holdout.csv` or `.parquet`).
    #[arg(long)]
    pub out: PathBuf,
    /// Where to write the truth (JSON); default: none written.
    #[arg(long)]
    pub truth: Option<PathBuf>,
    /// Sample rate, Hz.
    #[arg(long, default_value_t = 1000.0)]
    pub rate: f64,
    /// Clock jitter: each interval times a factor in 1 +- this (0.3: +-30 %).
    #[arg(long, default_value_t = 0.0)]
    pub jitter: f64,
    /// Fraction of rows whose values (whole row, positions or efforts) repeat the previous row's.
    #[arg(long, default_value_t = 0.0)]
    pub repeats: f64,
    /// Holes of 0.1 s (rows missing).
    #[arg(long, default_value_t = 0)]
    pub holes: usize,
    /// Glitches (1e300, a 50-sigma spike, a sign flipped).
    #[arg(long, default_value_t = 0)]
    pub glitches: usize,
    /// How late the position channel is against velocity and effort, s.
    #[arg(long, default_value_t = 0.0)]
    pub q_late: f64,
    /// How late the effort channel is against position and velocity, s.
    #[arg(long, default_value_t = 0.0)]
    pub tau_late: f64,
    /// The effect starts and stops: on only from START to END s (END left out: to the end of
    /// the record; an encoder that slips at START and keeps its offset). The held-out run has
    /// it a quarter of START earlier.
    #[arg(long, value_name = "START:END")]
    pub window: Option<String>,
    /// The nominal model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// A calibrated baseline: the robot that generates the data has it, the withheld effect on top.
    #[command(flatten)]
    pub baseline: BaselineArgs,
}

/// `diagnose`.
#[derive(Args, Debug, Default)]
pub struct DiagnoseArgs {
    /// Training data: CSV or CSV.gz, Parquet (the CSV's columns), a ROS 2 bag (a rosbag2
    /// directory, .mcap or .db3; see --topic); with --columns: a text matrix, a .npz or .npy,
    /// or a directory of one file per quantity.
    #[arg(long, requires = "holdout")]
    pub train: Option<PathBuf>,
    /// Held-out data (may be the training file with another window).
    #[arg(long, requires = "train")]
    pub holdout: Option<PathBuf>,
    /// Read recorded files in their own layout: where the time, positions, velocities
    /// (optional) and efforts are, in the robot's joint order, as
    /// `t=SRC,q=SRC[,qd=SRC],tau=SRC` with SRC = `[ENTRY][:COLUMNS][*SCALE]`: ENTRY a file of
    /// the directory or an array of the .npz, COLUMNS 1-based (`2-8`), SCALE a factor
    /// (`*1e-3` for milliseconds, `*-1` for the opposite sign).
    #[arg(long, value_name = "MAP", requires = "train")]
    pub columns: Option<String>,
    /// The topic of sensor_msgs/msg/JointState messages read from a ROS 2 bag
    /// (default /joint_states); other topics are skipped.
    #[arg(long, value_name = "NAME", requires = "train")]
    pub topic: Option<String>,
    /// Use only this part of the training data: START:END, seconds from its first sample.
    #[arg(long, value_name = "START:END", requires = "train")]
    pub train_window: Option<String>,
    /// Use only this part of the held-out data: START:END, seconds from its first sample.
    #[arg(long, value_name = "START:END", requires = "train")]
    pub holdout_window: Option<String>,
    /// Write the JSON report here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Write a readable report here: report.md with SVG plots (residual per joint with the gap
    /// windows, measured vs nominal vs corrected, the ranking) and report.json.
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
    /// Known effort noise, per-sample standard deviation (N m or N): one value, or one per
    /// joint separated by commas. Given, the noise floor comes from the stated noise
    /// (with --noise-q and --noise-qd, default 0) instead of noise levels estimated from the data.
    #[arg(long, value_delimiter = ',', value_name = "SIGMA[,..]")]
    pub noise_tau: Option<Vec<f64>>,
    /// Known position noise (rad or m), one value or one per joint; needs --noise-tau.
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "SIGMA[,..]",
        requires = "noise_tau"
    )]
    pub noise_q: Option<Vec<f64>>,
    /// Known velocity noise (rad/s or m/s), one value or one per joint; needs --noise-tau.
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "SIGMA[,..]",
        requires = "noise_tau"
    )]
    pub noise_qd: Option<Vec<f64>>,
    /// Hold a link correction the data take beyond every physical body at the nearest body
    /// (in the metric of the data) and name it if it holds on the held-out record, instead of
    /// leaving it out: for a nominal model whose inertial parameters are rough (a CAD model).
    #[arg(long)]
    pub hold_links: bool,
    /// Never hold link corrections to bodies, not even where the data ask for corrections
    /// without a body on most links (by default the model's inertials are then taken as rough
    /// and the corrections held): for a nominal model whose inertial parameters are trusted.
    #[arg(long, conflicts_with = "hold_links")]
    pub judge_links: bool,
    /// The nominal model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// A calibrated baseline: the diagnosis compares the data with the nominal model plus it,
    /// and names only what changed.
    #[command(flatten)]
    pub baseline: BaselineArgs,
}

impl DiagnoseArgs {
    /// The training and held-out files with their layout and windows.
    pub fn data_files(
        &self,
        train: PathBuf,
        holdout: PathBuf,
    ) -> Result<(crate::gap::DataFile, crate::gap::DataFile), Box<dyn std::error::Error>> {
        let columns = self
            .columns
            .as_deref()
            .map(str::parse::<dynamics_sim2real::data::import::ColumnMap>)
            .transpose()?;
        let window = |w: &Option<String>| w.as_deref().map(crate::gap::parse_window).transpose();
        Ok((
            crate::gap::DataFile {
                path: train,
                columns: columns.clone(),
                window: window(&self.train_window)?,
                topic: self.topic.clone(),
            },
            crate::gap::DataFile {
                path: holdout,
                columns,
                window: window(&self.holdout_window)?,
                topic: self.topic.clone(),
            },
        ))
    }

    /// The diagnosis's options these arguments set (the stated noise,
    /// `--hold-links`, `--judge-links`), the others at their defaults.
    pub fn options(&self) -> dynamics_sim2real::diagnose::Options {
        dynamics_sim2real::diagnose::Options {
            noise: self.noise(),
            hold_links: self.hold_links,
            judge_links: self.judge_links,
            ..Default::default()
        }
    }

    /// The stated sensor noise, if any.
    pub fn noise(&self) -> Option<dynamics_sim2real::diagnose::SensorNoise> {
        self.noise_tau
            .clone()
            .map(|tau| dynamics_sim2real::diagnose::SensorNoise {
                q: self.noise_q.clone().unwrap_or_else(|| vec![0.0]),
                qd: self.noise_qd.clone().unwrap_or_else(|| vec![0.0]),
                tau,
            })
    }
}

impl RobotCommand {
    /// The subcommand's name.
    pub fn name(&self) -> &'static str {
        match self {
            RobotCommand::Check(_) => "check",
            RobotCommand::Eval(_) => "eval",
            RobotCommand::Simulate(_) => "simulate",
            RobotCommand::Synth(_) => "synth",
            RobotCommand::Diagnose(_) => "diagnose",
            RobotCommand::Identify(_) => "identify",
            RobotCommand::Excite(_) => "excite",
            RobotCommand::CheckData(_) => "check-data",
        }
    }
}
