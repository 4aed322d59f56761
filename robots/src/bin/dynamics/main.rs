//! `dynamics`: the generic command-line program of `dynamics-cli` over the
//! built-in robots (`robots::builtin::Builtin`), chosen with `--robot`.
//!
//! ```text
//! dynamics                      # diagnose a built-in case (arm3r with a withheld effect)
//! dynamics check                # every robot of the source works against the shipped Pinocchio values
//! dynamics synth --robot NAME --effect KIND --joint J --out FILE.csv
//! dynamics diagnose --robot NAME --train A.csv --holdout B.csv [--json OUT.json] [--report DIR] [--baseline OLD.json]
//! dynamics simulate --robot NAME [--motion sines|chirp|pick-place|FILE.csv] [--effects FILE.json]
//! dynamics identify --robot NAME --train A.csv --holdout B.csv [--json OUT.json]
//! dynamics eval --robot NAME [--states FILE.json] [--out FILE.json] [--set NAME=VALUE]...
//! dynamics list                 # the robots it knows
//! dynamics new DIR --urdf FILE  # a crate for your own robot
//! ```

fn main() -> std::process::ExitCode {
    dynamics_cli::run_set("dynamics", &robots::builtin::Builtin)
}
