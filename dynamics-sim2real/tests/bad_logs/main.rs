//! Real logs as they come (issue 15), each damage with its message pinned:
//! an irregular clock, repeated samples, holes, glitches (and too many of
//! them), a time column in milliseconds, a file that ends in the middle of
//! a row, an effort column of the wrong sign, a record where nothing moves,
//! a joint whose velocity never reverses, a slow rate. One test binary:
//! the clock and rows (`clock.rs`), the values (`values.rs`), records that
//! hold too little (`motion.rs`); the logs are made here.

use dynamics_sim2real::data::{read_csv_str, write_csv, DataError, Measured};
use dynamics_sim2real::diagnose::{diagnose, DiagnoseError, Options, Report};
use dynamics_sim2real::effects::Effect;
use dynamics_sim2real::synth::{synthesize, Damage, SynthOptions};
use dynamics_sim2real::Warning;

mod clock;
#[path = "../common/mod.rs"]
mod common;
mod motion;
mod values;

use common::Arm2;

pub(crate) const JOINTS: [&str; 2] = ["j1", "j2"];

/// The synthesis options of every log here: 4 s of the two-link arm about
/// its home pose, at `rate` Hz, with `damage`.
pub(crate) fn opts(seed: u64, rate: f64, damage: Damage) -> SynthOptions<2> {
    SynthOptions {
        duration: 4.0,
        rate,
        home: [0.0, 0.4].into(),
        amplitude: [0.6, 0.6].into(),
        seed,
        damage,
        ..Default::default()
    }
}

/// `m` as the CSV text `synth` writes.
pub(crate) fn text(m: &Measured<2>) -> String {
    let mut out = Vec::new();
    write_csv(&mut out, m, &JOINTS).expect("writes");
    String::from_utf8(out).expect("utf8")
}

/// A log of the two-link arm with `effects`, as a CSV text.
pub(crate) fn log(effects: &[Effect], rate: f64, damage: Damage, seed: u64) -> String {
    text(&synthesize(&Arm2::default(), effects, &opts(seed, rate, damage)).expect("synthesizes"))
}

/// Reads a CSV text as the file `file`.
pub(crate) fn read(text: &str, file: &str) -> Result<Measured<2>, DataError> {
    read_csv_str(text, &JOINTS, file)
}

/// The diagnosis of training text `a` against held-out text `b`.
pub(crate) fn diagnosed(a: &str, b: &str) -> Result<Report, DiagnoseError> {
    let a = read(a, "a.csv").expect("reads");
    let b = read(b, "b.csv").expect("reads");
    diagnose(&Arm2::default(), &a, &b, &Options::default(), &|_, _| {})
}

/// The warnings as the user reads them.
pub(crate) fn messages(w: &[Warning]) -> Vec<String> {
    w.iter().map(ToString::to_string).collect()
}
